#pragma once
// The GL part of `shadowcert fuzz --gl` (docs/campaign.md, "The GL methods"): every case of the
// campaign rendered by the GL shadow methods in the view of campaign/campaign_view.h and compared
// with the exact image (pipeline/scene_comparison.h, the very function `shadowcert diff` runs).
// A robust method (cpu, cs, gs, ts, pertri) fails a case when its captured volume is open or
// it has a hard error; such failures are shrunk (campaign/soup_shrinker.h, the floor and camera
// held fixed) and written as a scene that `shadowcert diff` replays. With GlSceneSource::hard
// each case is a hard-soup scene (campaign/hard_scene.h) at a large size instead, shrunk on the
// pixels around its first hard pixel (campaign/window_comparison.h).
//
// GL contexts are per thread: everything here runs on the calling thread, whose context must
// be current; only the exact images inside use TBB.
#include <array>
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "pipeline/scene_comparison.h"
#include "core/scene.h"
#include "campaign/random_soup.h"
#include "campaign/campaign_view.h"
#include "campaign/case_shard.h"
#include "campaign/hard_scene.h"
#include "reference/exact_image.h"

namespace shadowcert {

// What each case renders: the random-soup case in its campaign view (campaign/campaign_view.h),
// or a hard-soup scene (campaign/hard_scene.h): `fuzz --gl --gl-scenes soups|hard`.
enum class GlSceneSource : std::uint8_t { soups, hard };

[[nodiscard]] std::string_view gl_scene_source_name(GlSceneSource source);  // "soups", "hard"

struct GlCampaignOptions {
  std::uint64_t seed = 1;
  std::uint64_t cases = 1;  // the whole campaign's: cases 0 .. cases-1
  CaseShard shard;          // only these of them (default: all)
  GlSceneSource scenes = GlSceneSource::soups;
  std::uint32_t triangles = 100;  // soups only: each case's soup (a hard scene sizes its own parts)
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
  // Hard scenes: a failing scene counts once for each part it holds (the soups' two above stay 0).
  std::vector<std::uint64_t> failures_by_part = std::vector<std::uint64_t>(kHardParts, 0);
};

struct GlCampaignFailure {
  std::uint64_t index = 0;  // the case
  std::size_t method = 0;   // index into the options' methods
  GlFailureKind kind = GlFailureKind::closure;
  // The first light that failed (soups: the case's only light) and, for hard errors, its first
  // hard pixel (column, row; row 0 at the top).
  std::size_t light = 0;
  std::array<std::uint32_t, 2> pixel{0, 0};
};

// A failure shrunk. Soups: the soup is a subset of the case's (unit frame) soup; light, floor
// and camera are the case's view's. Hard scenes: `scene` holds the floor, the parts' triangles
// that are left merged into one mesh "casters", the failing light alone and the scene's camera
// (its near plane kept); `pixels` are its hard pixels in the shrinking window, and `window` the
// one pixel it was shrunk to (the first of them).
struct ShrunkGlFailure {
  GlCampaignFailure failure;
  CampaignCase original;  // soups only
  CampaignView view;      // soups only: its soup replaced by the shrunk one
  Scene scene;            // hard scenes only
  std::vector<HardPart> parts;  // hard scenes only: the parts of the scene it was shrunk from
  std::vector<std::array<std::uint32_t, 2>> pixels;  // hard scenes, hard errors only
  PixelWindow window;                                // hard scenes only
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
  std::vector<std::uint64_t> cases_by_part = std::vector<std::uint64_t>(kHardParts, 0);  // hard scenes
  std::uint64_t cases_light_on_plane = 0;  // hard scenes whose first light lies in a triangle's plane
  std::uint64_t cases_edge_on = 0;         // hard scenes seen along a side face (HardSceneCase::edge_on_view)
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

// A failing scene shrunk, as the hard-scene campaign shrinks its failures: mesh `held_mesh`
// (the floor) kept as it is and first; every other mesh merged, in order, into one mesh
// "casters" whose triangles ddmin (campaign/soup_shrinker.h, at most 300 tests) removes while
// `method` still fails as `kind` says on light `light` alone (the scene's camera held, near
// plane included; `sign` for the GPU-built methods), judged on the pixels within 4 of `pixel`
// (campaign/window_comparison.h; any pixel for an open volume). `pixels` are then the shrunk
// scene's hard pixels in that window and `window` the first of them alone.
struct SceneShrink {
  Scene scene;  // meshes: the held one, then "casters"; the one light
  std::vector<std::array<std::uint32_t, 2>> pixels;
  PixelWindow window;
  std::size_t original_triangles = 0;  // of the casters
  std::size_t tests = 0;
  bool minimal = false;
};
[[nodiscard]] SceneShrink shrink_scene_failure(const Scene& scene, std::size_t held_mesh, std::size_t light,
                                               gpu::ShadowMethod method, GlFailureKind kind,
                                               std::array<std::uint32_t, 2> pixel, gpu::SignMode sign);

// The scene case `index` of the options renders (soups: its campaign view's scene; hard: its
// hard scene at the options' size).
[[nodiscard]] Scene gl_campaign_scene(const GlCampaignOptions& options, std::uint64_t index);

// A written reproducer: DIR/NAME.json (the scene), DIR/NAME.soup.off (hard scenes:
// NAME.casters.off) and DIR/NAME.floor.off.
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

// Writes the shrunk failure (names: gl-METHOD-sSEED-cINDEX, hard scenes gl-METHOD-hard-sSEED-cINDEX)
// and replays it.
[[nodiscard]] GlReproducer write_gl_reproducer(const std::filesystem::path& dir, const GlCampaignOptions& options,
                                               const ShrunkGlFailure& shrunk);

[[nodiscard]] std::string gl_run_name(gpu::ShadowMethod method);  // "gl-cs"

}  // namespace shadowcert
