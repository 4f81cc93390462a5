#pragma once
// Pictures of the edge ground truth and of an edge map against it (docs/edge-maps.md#scores), as
// gpu/image.h images for gpu/png_image.h (files, or an HTML report's data: URIs). Every picture
// is opaque, on white paper, with the pixels the centre ray sees a surface at in light gray, so
// that the scene shows through.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "gpu/image.h"
#include "pipeline/edge_map_comparison.h"
#include "reference/edge_ground_truth.h"
#include "reference/edge_scores.h"

namespace shadowcert {

// The ground truth: profile edge pixels black, inner edge pixels blue (0, 90, 255) (profile wins
// where both), excluded pixels of either class yellow (255, 200, 0); grazing pixels pale violet
// (225, 215, 245); other surface pixels light gray (232), background white.
[[nodiscard]] gpu::RgbaImage edge_truth_picture(const EdgeGroundTruth& truth);

// One class's intensities (width * height, in [0, 1]) as ink on paper: 255 (1 - intensity),
// gray. Throws std::invalid_argument("edge_intensity_picture: ...") on a size mismatch.
[[nodiscard]] gpu::RgbaImage edge_intensity_picture(std::span<const float> intensity, std::uint32_t width,
                                                    std::uint32_t height);

// The verdicts of one class at one threshold (reference/edge_scores.h's edge_verdicts): true
// detections green (0, 170, 0), false ones red (230, 0, 0) but magenta (200, 0, 200) on a
// grazing pixel, missed truth blue (0, 80, 255), truth found by a neighbouring detection pale
// green (150, 220, 150), excluded yellow (255, 200, 0); elsewhere the truth picture's paper.
// Throws std::invalid_argument("edge_verdict_picture: ...") when verdicts are not one per pixel.
[[nodiscard]] gpu::RgbaImage edge_verdict_picture(const EdgeGroundTruth& truth, std::span<const EdgeVerdict> verdicts);

// What `diff` shows of a comparison (pipeline/edge_map_comparison.h), named for files and the
// report: "edge_truth"; per filter F, "edge_F_profile_map" and "edge_F_inner_map" (the
// intensities), and "edge_F_C_verdicts" for C = profile, inner, any (1 px, at the filter's
// default thresholds, as edge_score_rows scores them: for any, a pixel where either channel
// passes its own).
struct NamedEdgePicture {
  std::string name;
  gpu::RgbaImage image;
};
[[nodiscard]] std::vector<NamedEdgePicture> edge_map_pictures(const EdgeMapComparison& comparison);

}  // namespace shadowcert
