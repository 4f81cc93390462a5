#pragma once
// The GL part of `shadowcert fuzz --gl` (docs/campaign.md, "The GL methods"): every case of the
// campaign rendered by the GL shadow methods in the view of campaign/campaign_view.h and compared
// with the exact image (pipeline/scene_comparison.h, the very function `shadowcert diff` runs).
// A robust method (cpu, cs, gs, ts, pertri) fails a case when its captured volume is open or
// it has a hard error; such failures are shrunk (campaign/soup_shrinker.h, the floor and camera
// held fixed) and written as a scene that `shadowcert diff` replays.
//
// GL contexts are per thread: everything here runs on the calling thread, whose context must
// be current; only the exact images inside use TBB.
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "pipeline/scene_comparison.h"
#include "core/scene.h"
#include "campaign/random_soup.h"
#include "campaign/campaign_view.h"
#include "campaign/case_shard.h"

namespace shadowcert {

struct GlCampaignOptions {
  std::uint64_t seed = 1;
  std::uint64_t cases = 1;  // the whole campaign's: cases 0 .. cases-1
  CaseShard shard;          // only these of them (default: all)
  std::uint32_t triangles = 100;
  std::vector<gpu::ShadowMethod> methods;  // at least one
  std::uint32_t width = 64;                // the image, >= 1 each
  std::uint32_t height = 48;
  std::size_t max_shrunk_per_method = 4;  // failing cases shrunk per method: the first by index
  gpu::SignMode sign = gpu::SignMode::exact;  // cs, gs, ts, pertri (gpu/sign_mode.h)
  std::atomic<std::uint64_t>* progress = nullptr;  // when set, incremented as cases complete
};

enum class GlFailureKind : std::uint8_t { closure, hard_errors };

// Per GL method; the case columns count cases, the pixel columns sum over them.
struct GlCampaignTally {
  std::uint64_t failures = 0;          // cases with an open volume or a hard error (robust methods)
  std::uint64_t closure_failures = 0;  // cases whose captured volume is open
  std::uint64_t hard_errors = 0;       // cases with at least one hard error
  std::uint64_t capacity_errors = 0;   // cases whose GPU-built volume overflowed its buffers
  std::uint64_t hard_error_pixels = 0, ambiguous_pixels = 0, agree_pixels = 0;
  std::uint64_t volume_triangles = 0;
  std::vector<std::uint64_t> failures_by_family = std::vector<std::uint64_t>(kSoupFamilies, 0);
  std::vector<std::uint64_t> failures_by_placement = std::vector<std::uint64_t>(kLightPlacements, 0);
};

struct GlCampaignFailure {
  std::uint64_t index = 0;  // the case
  std::size_t method = 0;   // index into the options' methods
  GlFailureKind kind = GlFailureKind::closure;
};

// A failure shrunk: the soup is a subset of the case's (unit frame) soup; light, floor and
// camera are the case's view's.
struct ShrunkGlFailure {
  GlCampaignFailure failure;
  CampaignCase original;
  CampaignView view;  // its soup replaced by the shrunk one
  std::size_t original_triangles = 0;
  std::size_t tests = 0;
  bool minimal = false;
};

struct GlCampaignResult {
  std::vector<GlCampaignTally> methods;  // one per method of the options
  std::uint64_t cases = 0;  // cases rendered: the shard's
  double seconds = 0.0;  // the cases alone, shrinking excluded
  double exact_seconds = 0.0;  // of which, the exact images (both roundings)
  double shrink_seconds = 0.0;
  std::vector<GlCampaignFailure> failures;  // sorted by (index, method)
  std::vector<ShrunkGlFailure> shrunk;  // at most max_shrunk_per_method per method
};

// The scene a case's view is rendered as: meshes "soup" then "floor", the one light, the
// camera.
[[nodiscard]] Scene campaign_view_scene(const CampaignView& view);

// Runs the GL part of the campaign and shrinks the first failures of each method. Needs a
// current GL context. Throws std::invalid_argument("run_gl_campaign: ...") on no method, an
// empty image or a bad shard.
[[nodiscard]] GlCampaignResult run_gl_campaign(const GlCampaignOptions& options);

// A written reproducer: DIR/NAME.json (the scene), DIR/NAME.soup.off and DIR/NAME.floor.off.
struct GlReproducer {
  std::string method;  // "gl-cs"
  std::uint64_t case_index = 0;
  std::string failure;  // "closure" or "hard_errors"
  std::size_t original_triangles = 0, triangles = 0;
  std::filesystem::path json;
  std::string command;  // shadowcert diff DIR/NAME.json --methods M [--sign float] (the scene holds the size)
  // Read back through the scene loader: bitwise the scene that failed, and `diff`'s
  // comparison on it fails the same way.
  bool replayed = false;
};

// Writes the shrunk failure (names: gl-METHOD-sSEED-cINDEX) and replays it.
[[nodiscard]] GlReproducer write_gl_reproducer(const std::filesystem::path& dir, const GlCampaignOptions& options,
                                               const ShrunkGlFailure& shrunk);

[[nodiscard]] std::string gl_run_name(gpu::ShadowMethod method);  // "gl-cs"

}  // namespace shadowcert
