#include "contour/tracking_variant.h"

#include <charconv>
#include <limits>

namespace shadowcert {

std::string tracking_variant_name(const TrackingVariant& variant) {
  switch (variant.search) {
    case TrackingSearch::full: return "full";
    case TrackingSearch::one_way: return "one-way";
    case TrackingSearch::continue_search: return "continue";
    case TrackingSearch::periodic: return "periodic:" + std::to_string(variant.period);
  }
  return "?";
}

std::optional<TrackingVariant> parse_tracking_variant(std::string_view name) {
  if (name == "full") return TrackingVariant{TrackingSearch::full, 0};
  if (name == "one-way") return TrackingVariant{TrackingSearch::one_way, 0};
  if (name == "continue") return TrackingVariant{TrackingSearch::continue_search, 0};
  constexpr std::string_view prefix = "periodic:";
  if (!name.starts_with(prefix)) return std::nullopt;
  const std::string_view digits = name.substr(prefix.size());
  std::uint64_t period = 0;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), period);
  if (digits.empty() || ec != std::errc() || end != digits.data() + digits.size() || period == 0 ||
      period > std::numeric_limits<std::uint32_t>::max())
    return std::nullopt;
  return TrackingVariant{TrackingSearch::periodic, static_cast<std::uint32_t>(period)};
}

}  // namespace shadowcert
