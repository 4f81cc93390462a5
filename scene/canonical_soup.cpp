#include "scene/canonical_soup.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <array>
#include <bit>
#include <compare>
#include <stdexcept>
#include <string>
#include <utility>

#include "core/huge_page_advice.h"

namespace shadowcert {
namespace {

// Sorting the input vertices by (position, input index) welds and orders in one pass: equal
// positions (bitwise, with -0 == +0: docs/definitions.md#inputs) become adjacent, and the
// lexicographic order of the groups is the canonical order. Each coordinate is compared as an
// unsigned integer that orders exactly as the doubles do (order_key). The input index makes
// every vertex distinct, so the sorted order is unique and any correct sort produces it.
//
// The sort has two steps. A radix sort orders (key of x, input index) records by the leading
// bits of the x key: the kRadixKeyBits highest of those that differ between two keys anywhere
// (radix_low_bit). Records equal on those bits (the same x, or an x within about 2^-21 of it
// relatively: few, and short, on real meshes) form runs, which a second step sorts by the full
// (x, y, z, input index). The radix passes run in parallel over fixed chunks of records whose
// histograms are laid out chunk after chunk within each digit, so every pass writes exactly
// what a sequential pass writes, on any number of threads; the runs are sorted in full, so
// their order depends on nothing else.

// Monotone map of finite doubles to unsigned integers: x < y iff key(x) < key(y), and
// key(-0) == key(+0) (both map to +0's pattern), exactly as double comparison treats them.
// Readers have rejected NaN (core/soup.h).
std::uint64_t order_key(double x) {
  const auto bits = std::bit_cast<std::uint64_t>(x == 0.0 ? 0.0 : x);
  constexpr std::uint64_t kSign = std::uint64_t{1} << 63;
  return (bits & kSign) != 0 ? ~bits : bits | kSign;
}

struct XRecord {
  std::uint64_t x_key;
  std::uint32_t input_index;
};

// Grain of the parallel loops and size of the radix sort's chunks.
constexpr std::size_t kGrain = std::size_t{1} << 16;
constexpr unsigned kDigitBits = 11;
constexpr std::size_t kDigits = std::size_t{1} << kDigitBits;
// Three passes of kDigitBits. Sorting all 64 bits took six on the 1M sphere grid's 500K
// vertices (9 ms of issue 24's 100 ms pipeline), though below these bits hardly any keys tie.
constexpr unsigned kRadixKeyBits = 3 * kDigitBits;

std::size_t chunk_count(std::size_t n) { return (n + kGrain - 1) / kGrain; }

// The lowest bit of the x keys the radix passes sort by: bits [low, 64) hold the kRadixKeyBits
// highest bits in which some two keys differ (every key lies between the least and the
// greatest, so the bits above bit_width(least ^ greatest) are the same in all).
unsigned radix_low_bit(std::uint64_t least, std::uint64_t greatest) {
  const auto differing = static_cast<unsigned>(std::bit_width(least ^ greatest));
  return differing > kRadixKeyBits ? differing - kRadixKeyBits : 0;
}

// Stable LSD radix sort of `records` by bits [low, 64) of x_key; `scratch` has the same size.
// The bits from low + kRadixKeyBits up are the same in every key (radix_low_bit), so no pass
// reads them; passes whose digit is the same in every key move nothing and are skipped.
void radix_sort_by_x(HugePageBuffer<XRecord>& records, HugePageBuffer<XRecord>& scratch, unsigned low) {
  const std::size_t n = records.size();
  const std::size_t chunks = chunk_count(n);
  std::vector<std::size_t> offset(chunks * kDigits);
  for (unsigned shift = low; shift < 64 && shift < low + kRadixKeyBits; shift += kDigitBits) {
    std::fill(offset.begin(), offset.end(), 0);
    tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t c) {
      std::size_t* count = offset.data() + c * kDigits;
      for (std::size_t i = c * kGrain; i < std::min(n, (c + 1) * kGrain); ++i)
        ++count[(records[i].x_key >> shift) & (kDigits - 1)];
    });
    // Digit-major prefix sum: digit d's records chunk by chunk, then digit d + 1's.
    std::size_t total = 0;
    bool uniform = false;
    for (std::size_t d = 0; d < kDigits; ++d)
      for (std::size_t c = 0; c < chunks; ++c) {
        std::size_t& slot = offset[c * kDigits + d];
        if (slot == n) uniform = true;
        total += std::exchange(slot, total);
      }
    if (uniform) continue;
    tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t c) {
      std::size_t* cursor = offset.data() + c * kDigits;
      for (std::size_t i = c * kGrain; i < std::min(n, (c + 1) * kGrain); ++i)
        scratch[cursor[(records[i].x_key >> shift) & (kDigits - 1)]++] = records[i];
    });
    records.swap(scratch);
  }
}

// Sorts each run of records equal on bits [low, 64) of x by (x, y, z, input index) and marks
// where each position group starts (new_group[i] != 0 iff record i's position differs from
// record i - 1's). Runs are independent: each chunk of records takes the runs that begin in it,
// in parallel. A run's keys are gathered once into a local array and sorted there by integers.
struct RunRecord {
  std::uint64_t x_key, y_key, z_key;
  std::uint32_t input_index;
  auto operator<=>(const RunRecord&) const = default;  // (x, y, z, input index)
};

bool same_position(const RunRecord& a, const RunRecord& b) {
  return a.x_key == b.x_key && a.y_key == b.y_key && a.z_key == b.z_key;
}

std::vector<char> sort_runs_and_mark_groups(const std::vector<Vec3>& vertices, HugePageBuffer<XRecord>& records,
                                            unsigned low) {
  const std::size_t n = records.size();
  std::vector<char> new_group;
  resize_huge(new_group, n);
  std::fill(new_group.begin(), new_group.end(), char{1});
  const auto run_begins = [&](std::size_t i) {
    return i == 0 || (records[i].x_key >> low) != (records[i - 1].x_key >> low);
  };
  tbb::parallel_for(std::size_t{0}, chunk_count(n), [&](std::size_t c) {
    std::vector<RunRecord> run;
    std::size_t i = c * kGrain;
    const std::size_t last = std::min(n, (c + 1) * kGrain);
    while (i < last && !run_begins(i)) ++i;  // that run belongs to an earlier chunk
    while (i < last) {
      std::size_t end = i + 1;
      while (end < n && !run_begins(end)) ++end;
      if (end - i > 1) {
        run.clear();
        for (std::size_t j = i; j < end; ++j) {
          const Vec3& p = vertices[records[j].input_index];
          run.push_back({records[j].x_key, order_key(p[1]), order_key(p[2]), records[j].input_index});
        }
        std::sort(run.begin(), run.end());
        for (std::size_t j = i; j < end; ++j) {
          records[j].input_index = run[j - i].input_index;
          if (j > i) new_group[j] = !same_position(run[j - i], run[j - i - 1]);
        }
      }
      i = end;
    }
  });
  return new_group;
}

// The first triangle holding an index >= n, or triangles.size() if none: found in parallel,
// reported as the sequential check would (the lowest such triangle).
std::size_t first_bad_triangle(const std::vector<Triangle>& triangles, std::size_t n) {
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, triangles.size(), kGrain), triangles.size(),
      [&](const tbb::blocked_range<std::size_t>& r, std::size_t found) {
        for (std::size_t t = r.begin(); t < r.end() && t < found; ++t)
          if (triangles[t][0] >= n || triangles[t][1] >= n || triangles[t][2] >= n) return t;
        return found;
      },
      [](std::size_t a, std::size_t b) { return std::min(a, b); });
}

}  // namespace

CanonicalSoup canonical_soup(const Soup& soup) {
  const std::size_t n = soup.vertices.size();
  const bool has_normals = !soup.normals.empty();
  if (has_normals && soup.normals.size() != n)
    throw std::invalid_argument("canonical_soup: normals must be empty or one per vertex");
  const std::size_t bad = first_bad_triangle(soup.triangles, n);
  if (bad < soup.triangles.size()) {
    const Triangle& t = soup.triangles[bad];
    const std::uint32_t v = t[0] >= n ? t[0] : t[1] >= n ? t[1] : t[2];
    throw std::invalid_argument("canonical_soup: triangle " + std::to_string(bad) + " has index " +
                                std::to_string(v) + " but the soup has " + std::to_string(n) + " vertices");
  }

  // The records, and the least and greatest x key.
  HugePageBuffer<XRecord> records(n), scratch(n);
  using KeyRange = std::pair<std::uint64_t, std::uint64_t>;
  const KeyRange keys = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, n, kGrain), KeyRange{~std::uint64_t{0}, 0},
      [&](const tbb::blocked_range<std::size_t>& r, KeyRange range) {
        for (std::size_t i = r.begin(); i < r.end(); ++i) {
          const std::uint64_t key = order_key(soup.vertices[i][0]);
          records[i] = {key, static_cast<std::uint32_t>(i)};
          range = {std::min(range.first, key), std::max(range.second, key)};
        }
        return range;
      },
      [](const KeyRange& a, const KeyRange& b) {
        return KeyRange{std::min(a.first, b.first), std::max(a.second, b.second)};
      });
  const unsigned low = n == 0 ? 0 : radix_low_bit(keys.first, keys.second);
  radix_sort_by_x(records, scratch, low);
  const std::vector<char> new_group = sort_runs_and_mark_groups(soup.vertices, records, low);

  // Group g's first record has the smallest input index of its position, whose coordinates (and
  // normal) are kept verbatim (a -0 stays -0), as weld_soup keeps them. In parallel: each chunk
  // of records counts its groups, then numbers them from its prefix offset.
  const std::size_t chunks = chunk_count(n);
  std::vector<std::size_t> first_group(chunks, 0);
  tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t c) {
    for (std::size_t i = c * kGrain; i < std::min(n, (c + 1) * kGrain); ++i) first_group[c] += new_group[i] != 0;
  });
  std::size_t groups = 0;
  for (std::size_t& g : first_group) groups += std::exchange(g, groups);

  CanonicalSoup out;
  // Each resize zero-fills (and first touches) its storage on one thread: side by side.
  tbb::parallel_invoke([&] { resize_huge(out.canonical_id, n); }, [&] { resize_huge(out.soup.vertices, groups); },
                       [&] {
                         if (has_normals) resize_huge(out.soup.normals, groups);
                       },
                       [&] { resize_huge(out.soup.triangles, soup.triangles.size()); });
  tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t c) {
    std::size_t group = first_group[c];  // the next group's number
    for (std::size_t i = c * kGrain; i < std::min(n, (c + 1) * kGrain); ++i) {
      const std::uint32_t input = records[i].input_index;
      if (new_group[i] != 0) {
        out.soup.vertices[group] = soup.vertices[input];
        if (has_normals) out.soup.normals[group] = soup.normals[input];
        ++group;
      }
      out.canonical_id[input] = static_cast<std::uint32_t>(group - 1);
    }
  });

  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, soup.triangles.size(), kGrain),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t t = r.begin(); t < r.end(); ++t) {
                        const Triangle& in = soup.triangles[t];
                        out.soup.triangles[t] = {out.canonical_id[in[0]], out.canonical_id[in[1]],
                                                 out.canonical_id[in[2]]};
                      }
                    });
  return out;
}

}  // namespace shadowcert
