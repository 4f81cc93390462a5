#pragma once
// How a silhouette tracker (contour/silhouette_tracker.h) finds each frame's silhouette edges
// (Chen and Tsai, §2.1 and §5; docs/smoothies.md, "Silhouette tracking"):
//   full       every edge, every frame (the exhaustive search tracking is measured against);
//   one-way    the paper's search: from each seed, follow one new silhouette edge at a time and
//              stop at an edge that touches a silhouette edge already found (misses the other
//              branches of a bifurcation, the paper's Figure 4);
//   continue   the fix the paper proposes in §5: do not stop at found edges, search the
//              neighbours of every silhouette edge found until none is left unchecked;
//   periodic:T one-way, and the full search on every T-th frame (frames 0, T, 2T, ...), so that
//              no edge stays missing for T frames or more.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace shadowcert {

enum class TrackingSearch : std::uint8_t { full, one_way, continue_search, periodic };

struct TrackingVariant {
  TrackingSearch search = TrackingSearch::full;
  std::uint32_t period = 0;  // periodic only, >= 1 (periodic:1 searches fully every frame)

  bool operator==(const TrackingVariant&) const = default;
};

// "full", "one-way", "continue", "periodic:T".
[[nodiscard]] std::string tracking_variant_name(const TrackingVariant& variant);

// The variant a name gives; nullopt for an unknown name or a period that is not a whole
// number in [1, 2^32 - 1] ("periodic:0", "periodic:x").
[[nodiscard]] std::optional<TrackingVariant> parse_tracking_variant(std::string_view name);

}  // namespace shadowcert
