#include "pipeline/edge_map_pictures.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "reference/exact_image.h"

namespace shadowcert {
namespace {

using Colour = std::array<std::uint8_t, 3>;

constexpr Colour kWhite{255, 255, 255};
constexpr Colour kSurface{232, 232, 232};
constexpr Colour kGrazing{225, 215, 245};
constexpr Colour kExcluded{255, 200, 0};

void put(gpu::RgbaImage& image, std::size_t pixel, const Colour& c) {
  std::uint8_t* p = image.pixels.data() + pixel * 4;
  p[0] = c[0];
  p[1] = c[1];
  p[2] = c[2];
  p[3] = 255;
}

// The paper every picture starts from: surfaces light gray, grazing ones pale violet.
gpu::RgbaImage paper(const EdgeGroundTruth& truth) {
  gpu::RgbaImage image(truth.width, truth.height);
  for (std::size_t p = 0; p < std::size_t{truth.width} * truth.height; ++p) {
    const bool surface = !truth.hit_triangles.empty() && truth.hit_triangles[p] != kNoHit;
    const bool grazing = !truth.grazing.empty() && truth.grazing[p] != 0;
    put(image, p, grazing ? kGrazing : surface ? kSurface : kWhite);
  }
  return image;
}

}  // namespace

gpu::RgbaImage edge_truth_picture(const EdgeGroundTruth& truth) {
  gpu::RgbaImage image = paper(truth);
  for (std::size_t p = 0; p < truth.profile.size(); ++p) {
    if (truth.profile[p] == EdgeTruth::edge) {
      put(image, p, {0, 0, 0});
    } else if (truth.inner[p] == EdgeTruth::edge) {
      put(image, p, {0, 90, 255});
    } else if (truth.profile[p] == EdgeTruth::excluded || truth.inner[p] == EdgeTruth::excluded) {
      put(image, p, kExcluded);
    }
  }
  return image;
}

gpu::RgbaImage edge_intensity_picture(std::span<const float> intensity, std::uint32_t width, std::uint32_t height) {
  if (intensity.size() != std::size_t{width} * height)
    throw std::invalid_argument("edge_intensity_picture: the intensities need width * height values");
  gpu::RgbaImage image(width, height);
  for (std::size_t p = 0; p < intensity.size(); ++p) {
    const float v = std::isnan(intensity[p]) ? 0.0f : std::clamp(intensity[p], 0.0f, 1.0f);
    const auto ink = static_cast<std::uint8_t>(std::lround(255.0 * (1.0 - v)));
    put(image, p, {ink, ink, ink});
  }
  return image;
}

gpu::RgbaImage edge_verdict_picture(const EdgeGroundTruth& truth, std::span<const EdgeVerdict> verdicts) {
  if (verdicts.size() != std::size_t{truth.width} * truth.height)
    throw std::invalid_argument("edge_verdict_picture: the verdicts need one value per pixel");
  gpu::RgbaImage image = paper(truth);
  for (std::size_t p = 0; p < verdicts.size(); ++p) {
    switch (verdicts[p]) {
      case EdgeVerdict::none:
        break;
      case EdgeVerdict::excluded:
        put(image, p, kExcluded);
        break;
      case EdgeVerdict::true_detection:
        put(image, p, {0, 170, 0});
        break;
      case EdgeVerdict::false_detection:
        put(image, p, !truth.grazing.empty() && truth.grazing[p] != 0 ? Colour{200, 0, 200} : Colour{230, 0, 0});
        break;
      case EdgeVerdict::missed:
        put(image, p, {0, 80, 255});
        break;
      case EdgeVerdict::found:
        put(image, p, {150, 220, 150});
        break;
    }
  }
  return image;
}

std::vector<NamedEdgePicture> edge_map_pictures(const EdgeMapComparison& comparison) {
  std::vector<NamedEdgePicture> out;
  const EdgeGroundTruth& truth = comparison.truth;
  out.push_back({"edge_truth", edge_truth_picture(truth)});
  for (const EdgeFilterRun& run : comparison.runs) {
    const std::string f(gpu::edge_filter_name(run.filter));
    out.push_back({"edge_" + f + "_profile_map", edge_intensity_picture(run.map.profile, truth.width, truth.height)});
    out.push_back({"edge_" + f + "_inner_map", edge_intensity_picture(run.map.inner, truth.width, truth.height)});
    // At the filter's default thresholds, as edge_score_rows scores it.
    const EdgeChannelThresholds fixed = default_edge_channel_thresholds(run.filter, comparison.crease_degrees);
    for (const EdgeClass c : kEdgeClasses) {
      const EdgeClassAtThresholds at = edge_class_at_thresholds(truth, run.map, c, fixed);
      const EdgeScoreInput input{truth.width, truth.height, at.images.truth, truth.grazing, at.images.intensity};
      out.push_back({"edge_" + f + "_" + std::string(edge_class_name(c)) + "_verdicts",
                     edge_verdict_picture(truth, edge_verdicts(input, 1, at.threshold))});
    }
  }
  return out;
}

}  // namespace shadowcert
