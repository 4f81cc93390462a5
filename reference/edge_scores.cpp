#include "reference/edge_scores.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <stdexcept>

namespace shadowcert {

double EdgeMatchCounts::precision() const {
  return detections == 0 ? 1.0 : static_cast<double>(true_detections) / static_cast<double>(detections);
}
double EdgeMatchCounts::recall() const {
  return truth == 0 ? 1.0 : static_cast<double>(found) / static_cast<double>(truth);
}
double EdgeMatchCounts::f1() const {
  const double p = precision(), r = recall();
  return p + r == 0.0 ? 0.0 : 2.0 * p * r / (p + r);
}
double EdgeMatchCounts::grazing_false_rate() const {
  return grazing_pixels == 0 ? 0.0 : static_cast<double>(grazing_false) / static_cast<double>(grazing_pixels);
}
EdgeMatchCounts& EdgeMatchCounts::operator+=(const EdgeMatchCounts& o) {
  detections += o.detections;
  true_detections += o.true_detections;
  truth += o.truth;
  found += o.found;
  grazing_false += o.grazing_false;
  grazing_pixels += o.grazing_pixels;
  return *this;
}

std::string EdgeTolerance::name() const {
  return matching == EdgeMatching::bsds ? std::string("bsds") : std::to_string(radius) + "px";
}

std::vector<EdgeTolerance> standard_edge_tolerances() {
  return {{EdgeMatching::window, 1, 0.0075}, {EdgeMatching::window, 2, 0.0075}, {EdgeMatching::bsds, 0, 0.0075}};
}

std::vector<double> default_edge_thresholds() {
  std::vector<double> t{0.001, 0.002, 0.003, 0.005, 0.0075, 0.01, 0.015, 0.02, 0.03, 0.04};
  for (int k = 1; k <= 19; ++k) t.push_back(k * 0.05);
  return t;
}

namespace {

void validate(const EdgeScoreInput& in, const EdgeTolerance& tolerance) {
  const std::size_t n = std::size_t{in.width} * in.height;
  if (in.truth.size() != n || in.intensity.size() != n || (!in.grazing.empty() && in.grazing.size() != n))
    throw std::invalid_argument("score_edges: truth, intensity and grazing need width * height values");
  if (tolerance.matching == EdgeMatching::bsds && !(tolerance.bsds_fraction > 0.0 && tolerance.bsds_fraction < 1.0))
    throw std::invalid_argument("score_edges: the bsds fraction must lie in (0, 1)");
}

bool grazing_at(const EdgeScoreInput& in, std::size_t p) { return !in.grazing.empty() && in.grazing[p] != 0; }

// Per pixel: the largest value of `values` over the pixels whose `keep` is set within
// Chebyshev distance `radius` (-infinity where none): two separable passes of a running max.
std::vector<float> window_max(std::span<const float> values, std::span<const std::uint8_t> keep, std::uint32_t w,
                              std::uint32_t h, std::uint32_t radius) {
  constexpr float kNone = -std::numeric_limits<float>::infinity();
  std::vector<float> rows(values.size(), kNone), out(values.size(), kNone);
  const auto r = static_cast<std::int64_t>(radius);
  for (std::uint32_t y = 0; y < h; ++y)
    for (std::int64_t x = 0; x < w; ++x) {
      float m = kNone;
      for (std::int64_t k = std::max<std::int64_t>(0, x - r); k <= std::min<std::int64_t>(w - 1, x + r); ++k) {
        const std::size_t p = std::size_t{y} * w + static_cast<std::size_t>(k);
        if (keep[p] != 0 && values[p] > m) m = values[p];
      }
      rows[std::size_t{y} * w + static_cast<std::size_t>(x)] = m;
    }
  for (std::int64_t y = 0; y < h; ++y)
    for (std::uint32_t x = 0; x < w; ++x) {
      float m = kNone;
      for (std::int64_t k = std::max<std::int64_t>(0, y - r); k <= std::min<std::int64_t>(h - 1, y + r); ++k)
        m = std::max(m, rows[static_cast<std::size_t>(k) * w + x]);
      out[static_cast<std::size_t>(y) * w + x] = m;
    }
  return out;
}

std::vector<EdgeMatchCounts> window_scores(const EdgeScoreInput& in, std::uint32_t radius,
                                           std::span<const double> thresholds) {
  const std::size_t n = in.truth.size();
  std::vector<std::uint8_t> is_truth(n), everywhere(n, 1);
  std::vector<float> truth_value(n);
  for (std::size_t p = 0; p < n; ++p) {
    is_truth[p] = in.truth[p] == EdgeTruth::edge;
    truth_value[p] = is_truth[p] ? 1.0f : 0.0f;
  }
  // A truth pixel in reach of p; the strongest detection in reach of p.
  const std::vector<float> near_truth = window_max(truth_value, is_truth, in.width, in.height, radius);
  const std::vector<float> near_detection = window_max(in.intensity, everywhere, in.width, in.height, radius);
  std::vector<EdgeMatchCounts> out(thresholds.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, thresholds.size(), 1), [&](const auto& range) {
    for (std::size_t k = range.begin(); k != range.end(); ++k) {
      const double t = thresholds[k];
      EdgeMatchCounts c;
      for (std::size_t p = 0; p < n; ++p) {
        const bool reach = near_truth[p] > 0.0f;
        if (is_truth[p]) {
          ++c.truth;
          if (static_cast<double>(near_detection[p]) > t) ++c.found;
        }
        if (in.truth[p] == EdgeTruth::excluded) continue;
        const bool detected = static_cast<double>(in.intensity[p]) > t;
        const bool grazing = grazing_at(in, p);
        if (grazing && !is_truth[p]) ++c.grazing_pixels;
        if (!detected) continue;
        ++c.detections;
        if (reach) {
          ++c.true_detections;
        } else if (grazing) {
          ++c.grazing_false;
        }
      }
      out[k] = c;
    }
  });
  return out;
}

// Maximum bipartite matching (Hopcroft and Karp) between left nodes and right nodes, given each
// left node's neighbours; returns the number of matched pairs and, per left node, its partner.
std::size_t maximum_matching(const std::vector<std::vector<std::uint32_t>>& adjacent, std::size_t right,
                             std::vector<std::uint32_t>& left_partner) {
  constexpr std::uint32_t kFree = std::numeric_limits<std::uint32_t>::max();
  const std::size_t left = adjacent.size();
  left_partner.assign(left, kFree);
  std::vector<std::uint32_t> right_partner(right, kFree), layer(left);
  std::size_t matched = 0;
  // Greedy start.
  for (std::uint32_t l = 0; l < left; ++l)
    for (std::uint32_t r : adjacent[l])
      if (right_partner[r] == kFree) {
        left_partner[l] = r;
        right_partner[r] = l;
        ++matched;
        break;
      }
  constexpr std::uint32_t kUnreached = std::numeric_limits<std::uint32_t>::max();
  while (true) {
    // BFS layers from the free left nodes over alternating paths.
    std::deque<std::uint32_t> queue;
    for (std::uint32_t l = 0; l < left; ++l) {
      layer[l] = left_partner[l] == kFree ? 0 : kUnreached;
      if (layer[l] == 0) queue.push_back(l);
    }
    bool reached_free = false;
    while (!queue.empty()) {
      const std::uint32_t l = queue.front();
      queue.pop_front();
      for (std::uint32_t r : adjacent[l]) {
        const std::uint32_t next = right_partner[r];
        if (next == kFree) {
          reached_free = true;
        } else if (layer[next] == kUnreached) {
          layer[next] = layer[l] + 1;
          queue.push_back(next);
        }
      }
    }
    if (!reached_free) break;
    // Iterative DFS along the layers from each free left node.
    std::vector<std::size_t> cursor(left, 0);
    std::size_t augmented = 0;
    for (std::uint32_t root = 0; root < left; ++root) {
      if (left_partner[root] != kFree) continue;
      std::vector<std::uint32_t> path{root};  // left nodes on the current path
      while (!path.empty()) {
        const std::uint32_t l = path.back();
        bool advanced = false;
        while (cursor[l] < adjacent[l].size()) {
          const std::uint32_t r = adjacent[l][cursor[l]++];
          const std::uint32_t next = right_partner[r];
          if (next == kFree) {
            // Augment along the path: each left node takes the right node it went through.
            std::uint32_t take = r;
            for (std::size_t i = path.size(); i-- > 0;) {
              const std::uint32_t node = path[i];
              const std::uint32_t previous = left_partner[node];
              left_partner[node] = take;
              right_partner[take] = node;
              take = previous;
            }
            ++augmented;
            path.clear();
            advanced = true;
            break;
          }
          if (layer[next] == layer[l] + 1) {
            path.push_back(next);
            advanced = true;
            break;
          }
        }
        if (!advanced) {
          layer[l] = kUnreached;  // a dead end for this phase
          path.pop_back();
        }
      }
    }
    if (augmented == 0) break;
    matched += augmented;
  }
  return matched;
}

EdgeMatchCounts bsds_score(const EdgeScoreInput& in, double fraction, double threshold) {
  const std::uint32_t w = in.width, h = in.height;
  const std::size_t n = in.truth.size();
  std::vector<std::uint8_t> detected(n), truth(n);
  for (std::size_t p = 0; p < n; ++p) {
    detected[p] = static_cast<double>(in.intensity[p]) > threshold;
    truth[p] = in.truth[p] == EdgeTruth::edge;
  }
  detected = thin_edges(detected, w, h);
  truth = thin_edges(truth, w, h);
  const double diagonal = std::sqrt(static_cast<double>(w) * w + static_cast<double>(h) * h);
  const double reach = fraction * diagonal;
  const auto r = static_cast<std::int64_t>(std::floor(reach));
  std::vector<std::array<std::int64_t, 2>> offsets;  // within `reach`, nearest first
  for (std::int64_t dy = -r; dy <= r; ++dy)
    for (std::int64_t dx = -r; dx <= r; ++dx)
      if (static_cast<double>(dx * dx + dy * dy) <= reach * reach) offsets.push_back({dx, dy});
  std::stable_sort(offsets.begin(), offsets.end(), [](const auto& a, const auto& b) {
    return a[0] * a[0] + a[1] * a[1] < b[0] * b[0] + b[1] * b[1];
  });
  std::vector<std::uint32_t> truth_id(n, std::numeric_limits<std::uint32_t>::max());
  std::uint32_t truth_count = 0;
  for (std::size_t p = 0; p < n; ++p)
    if (truth[p] != 0) truth_id[p] = truth_count++;
  std::vector<std::size_t> detection_pixel;
  std::vector<std::vector<std::uint32_t>> adjacent;
  for (std::uint32_t y = 0; y < h; ++y)
    for (std::uint32_t x = 0; x < w; ++x) {
      const std::size_t p = std::size_t{y} * w + x;
      if (detected[p] == 0 || in.truth[p] == EdgeTruth::excluded) continue;
      detection_pixel.push_back(p);
      std::vector<std::uint32_t> near;
      for (const auto& [dx, dy] : offsets) {
        const std::int64_t qx = x + dx, qy = y + dy;
        if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
        const std::size_t q = static_cast<std::size_t>(qy) * w + static_cast<std::size_t>(qx);
        if (truth[q] != 0) near.push_back(truth_id[q]);
      }
      adjacent.push_back(std::move(near));
    }
  std::vector<std::uint32_t> partner;
  const std::size_t matched = maximum_matching(adjacent, truth_count, partner);
  EdgeMatchCounts c;
  c.detections = detection_pixel.size();
  c.true_detections = matched;
  c.truth = truth_count;
  c.found = matched;
  // Grazing: false detections on grazing pixels; the grazing pixels off the truth.
  for (std::size_t k = 0; k < detection_pixel.size(); ++k)
    if (partner[k] == std::numeric_limits<std::uint32_t>::max() && grazing_at(in, detection_pixel[k])) ++c.grazing_false;
  for (std::size_t p = 0; p < n; ++p)
    if (grazing_at(in, p) && in.truth[p] == EdgeTruth::none) ++c.grazing_pixels;
  return c;
}

}  // namespace

std::vector<EdgeMatchCounts> score_edges(const EdgeScoreInput& input, const EdgeTolerance& tolerance,
                                         std::span<const double> thresholds) {
  validate(input, tolerance);
  if (tolerance.matching == EdgeMatching::window) return window_scores(input, tolerance.radius, thresholds);
  std::vector<EdgeMatchCounts> out(thresholds.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, thresholds.size(), 1), [&](const auto& range) {
    for (std::size_t k = range.begin(); k != range.end(); ++k) out[k] = bsds_score(input, tolerance.bsds_fraction, thresholds[k]);
  });
  return out;
}

std::vector<EdgeVerdict> edge_verdicts(const EdgeScoreInput& input, std::uint32_t radius, double threshold) {
  validate(input, EdgeTolerance{EdgeMatching::window, radius, 0.0075});
  const std::size_t n = input.truth.size();
  std::vector<std::uint8_t> is_truth(n), everywhere(n, 1);
  std::vector<float> truth_value(n);
  for (std::size_t p = 0; p < n; ++p) {
    is_truth[p] = input.truth[p] == EdgeTruth::edge;
    truth_value[p] = is_truth[p] ? 1.0f : 0.0f;
  }
  const std::vector<float> near_truth = window_max(truth_value, is_truth, input.width, input.height, radius);
  const std::vector<float> near_detection = window_max(input.intensity, everywhere, input.width, input.height, radius);
  std::vector<EdgeVerdict> out(n, EdgeVerdict::none);
  for (std::size_t p = 0; p < n; ++p) {
    const bool detected = static_cast<double>(input.intensity[p]) > threshold;
    if (input.truth[p] == EdgeTruth::excluded) {
      out[p] = EdgeVerdict::excluded;
    } else if (detected) {
      out[p] = near_truth[p] > 0.0f ? EdgeVerdict::true_detection : EdgeVerdict::false_detection;
    } else if (is_truth[p]) {
      out[p] = static_cast<double>(near_detection[p]) > threshold ? EdgeVerdict::found : EdgeVerdict::missed;
    }
  }
  return out;
}

std::vector<std::uint8_t> thin_edges(std::span<const std::uint8_t> mask, std::uint32_t width, std::uint32_t height) {
  if (mask.size() != std::size_t{width} * height)
    throw std::invalid_argument("thin_edges: the mask needs width * height values");
  const auto w = static_cast<std::int64_t>(width), h = static_cast<std::int64_t>(height);
  std::vector<std::uint8_t> m(mask.size());
  for (std::size_t p = 0; p < mask.size(); ++p) m[p] = mask[p] != 0;
  const auto at = [&](std::int64_t x, std::int64_t y) -> int {
    return x < 0 || y < 0 || x >= w || y >= h ? 0 : m[static_cast<std::size_t>(y * w + x)];
  };
  // Only a pixel with a 4-neighbour unset can be removed (G1 needs one), so each sub-iteration
  // examines the set pixels next to an unset one: at first every such pixel, then those of the
  // last candidates still set and the set 4-neighbours of what was removed. The same pixels are
  // removed as by scanning the whole image each time.
  std::vector<std::uint32_t> candidates, next, remove;
  std::vector<std::uint32_t> stamp(m.size(), 0);
  std::uint32_t round = 1;
  const auto unset_4_neighbour = [&](std::int64_t x, std::int64_t y) {
    return at(x + 1, y) == 0 || at(x - 1, y) == 0 || at(x, y + 1) == 0 || at(x, y - 1) == 0;
  };
  for (std::int64_t y = 0; y < h; ++y)
    for (std::int64_t x = 0; x < w; ++x)
      if (m[static_cast<std::size_t>(y * w + x)] != 0 && unset_4_neighbour(x, y))
        candidates.push_back(static_cast<std::uint32_t>(y * w + x));
  int idle = 0;  // consecutive sub-iterations that removed nothing
  for (int pass = 0; idle < 2 && !candidates.empty(); pass ^= 1) {
    remove.clear();
    for (const std::uint32_t q : candidates) {
      const std::int64_t x = q % w, y = q / w;
      // x1 .. x8 counter-clockwise from the east (rows grow downwards), x[8] = x1 again.
      const int n[9] = {at(x + 1, y),     at(x + 1, y - 1), at(x, y - 1),     at(x - 1, y - 1), at(x - 1, y),
                        at(x - 1, y + 1), at(x, y + 1),     at(x + 1, y + 1), at(x + 1, y)};
      // G1: one 8-connected component among the neighbours (the crossing number X_H is 1).
      int crossings = 0;
      for (int i = 0; i < 4; ++i) crossings += n[2 * i] == 0 && (n[2 * i + 1] != 0 || n[2 * i + 2] != 0);
      if (crossings != 1) continue;
      // G2: 2 <= min(n1, n2) <= 3 (an end point is kept, an interior one too).
      int n1 = 0, n2 = 0;
      for (int k = 0; k < 4; ++k) {
        n1 += (n[2 * k] | n[2 * k + 1]) != 0;
        n2 += (n[2 * k + 1] | n[2 * k + 2]) != 0;
      }
      const int least = std::min(n1, n2);
      if (least < 2 || least > 3) continue;
      // G3 (first sub-iteration) and G3' (second): north-east and south-west boundaries.
      const bool removable = pass == 0 ? ((n[1] | n[2] | (1 - n[7])) & n[0]) == 0
                                       : ((n[5] | n[6] | (1 - n[3])) & n[4]) == 0;
      if (removable) remove.push_back(q);
    }
    for (const std::uint32_t q : remove) m[q] = 0;
    idle = remove.empty() ? idle + 1 : 0;
    // The next candidates: the surviving ones, and the set 4-neighbours of the removed.
    ++round;
    next.clear();
    const auto keep = [&](std::int64_t x, std::int64_t y) {
      if (x < 0 || y < 0 || x >= w || y >= h) return;
      const auto q = static_cast<std::uint32_t>(y * w + x);
      if (m[q] == 0 || stamp[q] == round) return;
      stamp[q] = round;
      next.push_back(q);
    };
    for (const std::uint32_t q : candidates) keep(q % w, q / w);
    for (const std::uint32_t q : remove) {
      const std::int64_t x = q % w, y = q / w;
      keep(x + 1, y);
      keep(x - 1, y);
      keep(x, y + 1);
      keep(x, y - 1);
    }
    candidates.swap(next);
  }
  return m;
}

std::size_t best_threshold(std::span<const std::vector<EdgeMatchCounts>> curves) {
  if (curves.empty() || curves.front().empty()) throw std::invalid_argument("best_threshold: no curve");
  const std::size_t n = curves.front().size();
  for (const auto& c : curves)
    if (c.size() != n) throw std::invalid_argument("best_threshold: the curves differ in length");
  std::size_t best = 0;
  double best_f = -1.0;
  for (std::size_t k = 0; k < n; ++k) {
    EdgeMatchCounts sum;
    for (const auto& c : curves) sum += c[k];
    if (sum.f1() > best_f) {
      best_f = sum.f1();
      best = k;
    }
  }
  return best;
}

}  // namespace shadowcert
