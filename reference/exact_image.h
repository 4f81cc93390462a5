#pragma once
// The exact image (docs/definitions.md#pixel-protocol): what a shadow renderer must show at every pixel, decided with
// exact predicates on the input doubles, against which `shadowcert diff` checks each GL method.
//
// For each pixel the ray through its centre (core/pixel_ray.h, the GL path's own rays) is
// followed to its first hit P: which triangle the ray meets first is decided by orientation
// signs and by an exact comparison of ray parameters (an interval filter, then exact binary
// floats), never by a rounded distance. P is never rounded: it is the rational point
// e + (N / D) d, kept as an interval enclosure for filters and as exact homogeneous
// coordinates for the rare signs the enclosure cannot decide. For each light, n(P) is the
// number of casting triangles (s != 0, docs/definitions.md#orientation) crossed by the open segment P -> light (the ray
// towards l for w = 0), the hit triangle excluded (docs/definitions.md#pixel-protocol).
// A triangle that ExactImageOptions::casts marks as receiving only (a mesh with "casts": false,
// core/scene.h) is seen, hit and hides what lies behind it, and has its own terminator, but it
// is in no volume: it is never counted, and its edges are no silhouette and no volume face.
//
// A pixel is AMBIGUOUS (docs/definitions.md#pixel-protocol) when the exact answer at its centre does not pin down what a
// correct renderer shows there:
//   - its footprint does not see one triangle: the footprint rays (the four corner rays and the
//     centre ray) see different triangles (or some none), or, where they agree on triangle h,
//     an edge of another triangle crosses the eye pyramid over the footprint's region R on h
//     (reference/detail/pixel_footprint.h: a small triangle between the rays);
//   - n is not constant over the footprint: the footprint rays count differently, or a
//     silhouette edge (the shadow-volume chain's side faces) crosses the light pyramid over R
//     (a shadow sliver between the rays, which GL's finite depth precision may draw over the
//     centre);
//   - the light is not strictly on the eye's side of the hit triangle's plane (the self-shadow
//     terminator: P then lies on the boundary of that triangle's own volume);
//   - a zero sign arose on a footprint ray (through an edge or a vertex, two triangles met at
//     one point, P's segment to the light touching a volume boundary).
// Corner rays are shared by the four pixels around them: (width + 1) x (height + 1) corners are
// traced once. Every test is exact (interval filters, exact fallbacks): the image does not
// change under vertex relabelling, face reversal or an exact translation of scene and camera.
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "core/camera.h"
#include "core/light.h"
#include "core/soup.h"

namespace shadowcert {

// hit_triangles and counts where the centre ray meets no triangle.
inline constexpr std::uint32_t kNoHit = 0xFFFFFFFFu;
// counts where n(P) is undefined: P on a boundary (a zero sign on the centre ray).
inline constexpr std::uint32_t kUndefinedCount = 0xFFFFFFFEu;

// Why a pixel is ambiguous, as bits (0: unambiguous); several may be set.
enum AmbiguityReason : std::uint8_t {
  kFootprintTriangles = 1,  // footprint rays see different triangles (or some none), or another
                            // triangle's edge crosses the footprint's eye pyramid
  kFootprintCounts = 2,     // all see one triangle, with different n, or a silhouette edge
                            // crosses the footprint's light pyramid
  kTerminator = 4,          // the light is not strictly on the eye's side of the hit plane
  kZeroSign = 8,            // a footprint ray meets an edge, a vertex, a tie or a touched boundary
  kInputRounding = 16,      // the scene rounded to float answers otherwise (reference/input_rounding.h)
  kDepthBand = 32,          // a surface or a volume face within ExactImageOptions::depth_band of P
  kOutsideWindow = 64,      // not imaged: outside ExactImageOptions::window
};

// A rectangle of pixels: columns [x, x + width), rows [y, y + height), row 0 at the top.
struct PixelWindow {
  std::uint32_t x = 0;
  std::uint32_t y = 0;
  std::uint32_t width = 0;
  std::uint32_t height = 0;
};

// One light's images; pixels row-major, row 0 at the TOP (as gpu/image.h).
struct ExactLightImage {
  std::vector<std::uint32_t> counts;    // n(P); kNoHit or kUndefinedCount
  std::vector<std::uint8_t> lit;        // 255 where the centre ray hits and n(P) == 0, else 0
  std::vector<std::uint8_t> ambiguity;  // AmbiguityReason bits
};

// Over every light of one call, per pixel (ExactImageOptions::light_images false): what the soft
// reference reads of the per-light images (reference/soft_shadow_image.h), summed as the counts
// come, so that no per-light image is held (6 bytes per pixel and light).
struct ExactLightTally {
  std::vector<std::uint32_t> defined;    // lights whose count is defined: neither kNoHit nor kUndefinedCount
  std::vector<std::uint32_t> lit;        // of those, the lights with n(P) == 0 (lit 255)
  std::vector<std::uint8_t> terminator;  // 1 where some light's ambiguity has kTerminator, else 0
};

struct ExactImageStats {
  std::uint64_t rays = 0;    // centre and corner rays traced
  std::uint64_t counts = 0;  // n(P) evaluations, all lights (centres, and corners that decide)
  double tree_seconds = 0.0;   // casting signs, silhouettes and the box tree
  double hit_seconds = 0.0;        // first hits of every ray
  double footprint_seconds = 0.0;  // eye pyramids: is only the hit triangle seen over each pixel
  double count_seconds = 0.0;      // counts, light pyramids and the ambiguity bits
  double seconds = 0.0;        // all of it
};

struct ExactImage {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  // The centre ray's first hit: an index into the soup's triangles, or kNoHit. Where the first
  // contact is degenerate (kZeroSign) it is the smallest index among the triangles met there.
  std::vector<std::uint32_t> hit_triangles;
  // The light-independent AmbiguityReason bits of each pixel, which every light's ambiguity
  // includes: kZeroSign (a footprint ray's first contact is degenerate; with
  // ExactImageOptions::footprints false, the centre ray's), kFootprintTriangles (the footprint
  // sees more than one triangle, or some of it nothing) and kDepthBand's surface test. Zero:
  // the footprint sees one triangle only (or, all of it, nothing). What the edge ground truth
  // reads (reference/edge_ground_truth.h), with no light at all.
  std::vector<std::uint8_t> view_ambiguity;
  std::vector<ExactLightImage> lights;  // one per light, in the given order (none without light_images)
  ExactLightTally tally;                // only without ExactImageOptions::light_images
  ExactImageStats stats;
};

// The progress stage of the counts when every light is counted in one pass (footprints false
// and several point lights: the soft reference's samples, counted together per hit point).
inline constexpr std::string_view kAllLightsCounts = "counts of all lights";

struct ExactImageOptions {
  // Called as work advances with the stage ("hits", "footprints", then "counts" per light, or,
  // where every light is counted in one pass, kAllLightsCounts once, its total the counts of
  // all lights), the work done and the total of that stage: from worker threads, never two at
  // once, about once per percent. Empty: no reports.
  std::function<void(std::string_view stage, std::uint64_t done, std::uint64_t total)> progress;

  // The depth band of a renderer whose depth test has finite precision (the diff's model of
  // GL's depth buffer, pipeline/scene_comparison.cpp). When set, depth_band(D) > 0 is a half-width in
  // view depth around P at view depth D; a pixel whose centre ray meets, within that band of
  // P, another triangle (two surfaces a depth buffer cannot order) or the side face of an
  // edge of a casting triangle (a shadow-volume face whose depth test against P a renderer
  // may get either way: silhouette edges for every volume method, the others for pertri,
  // which draws them as cancelling pairs) is ambiguous: kDepthBand. The band's end points are
  // rounded to doubles, which only moves the band by an ulp; the tests on them are exact.
  std::function<double(double view_depth)> depth_band;

  // Which triangles cast: one flag per soup triangle, 0 for a triangle that only receives;
  // empty: every triangle casts. Only casting triangles are counted in n(P), and only they
  // make the silhouettes and the depth band's volume faces; every triangle is seen.
  std::vector<std::uint8_t> casts;

  // false: only what the centre rays decide, for callers that read nothing else (the soft
  // reference, reference/soft_shadow_image.h, about 3x faster): no corner ray is traced and no
  // footprint, light pyramid or depth band is tested (depth_band is not read); the counts and
  // lit masks are the same, and the ambiguity keeps only kZeroSign (at the centre) and
  // kTerminator.
  bool footprints = true;

  // Only the pixels of this window are imaged (their centre and corner rays traced, as in the
  // whole image, so each of them gets exactly the answer the whole image gives it); every other
  // pixel has no hit, count kNoHit, lit 0 and the ambiguity kOutsideWindow, so a comparison
  // judges none of them. Shrinking a GL failure at a large size (campaign/gl_campaign.h) images
  // the few pixels around the failing one. nullopt: every pixel. The window must lie inside the
  // image and not be empty.
  std::optional<PixelWindow> window;

  // false: `lights` stays empty and `tally` sums the per-light images over the lights instead
  // (the same verdicts), so that memory does not grow with the number of lights: the soft
  // reference's samples. With footprints false and several point lights the per-light images
  // are never made; otherwise each is made and summed in turn.
  bool light_images = true;
};

// The exact image of `soup` (every triangle receives; those options.casts allows, all by
// default, cast; world space) for `camera` and each of `lights`. Parallel over rows (TBB).
// Throws std::invalid_argument("exact_image: ...") for a vertex index out of range, a
// non-finite coordinate, a light with w not in {0, 1} or a zero direction, a degenerate
// camera (core/pixel_ray.h), casts neither empty nor one flag per triangle, or a window that is
// empty or not inside the image.
[[nodiscard]] ExactImage exact_image(const Soup& soup, std::span<const Light> lights, const Camera& camera,
                                     const ExactImageOptions& options = {});

}  // namespace shadowcert
