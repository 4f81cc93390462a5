#include "cli/option_values.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>

#include "pipeline/method_registry.h"

namespace shadowcert::cli {

void apply_image_size(const std::string& size, Camera& camera, const std::string& option) {
  if (size.empty()) return;
  const auto x = size.find('x');
  unsigned long w = 0, h = 0;
  try {
    if (x == std::string::npos) throw std::invalid_argument("no x");
    std::size_t used_w = 0, used_h = 0;
    w = std::stoul(size.substr(0, x), &used_w);
    h = std::stoul(size.substr(x + 1), &used_h);
    if (used_w != x || used_h != size.size() - x - 1) throw std::invalid_argument("trailing");
  } catch (const std::exception&) {
    throw CLI::ValidationError(option, "expects WxH, e.g. 1024x768");
  }
  if (w == 0 || h == 0 || w > kMaxImageSide || h > kMaxImageSide)
    throw CLI::ValidationError(option, "each side must be in [1, " + std::to_string(kMaxImageSide) + "]");
  camera.width = static_cast<std::uint32_t>(w);
  camera.height = static_cast<std::uint32_t>(h);
}

void check_light_angle(double degrees, bool zero_allowed, const std::string& option) {
  const bool low_ok = zero_allowed ? degrees >= 0.0 : degrees > 0.0;
  if (!std::isfinite(degrees) || !low_ok || !(degrees < gpu::kMaxLightAngleDegrees))
    throw CLI::ValidationError(option, std::string("must be in ") + (zero_allowed ? "[0" : "(0") +
                                           ", 90) degrees (a directional light's angular radius), got " +
                                           std::to_string(degrees));
}

gpu::ShadowMethod shadow_method_option(const std::string& name, const std::string& option) {
  if (const MethodEntry* entry = find_method(name)) return entry->method;
  if (find_ray_traced_method(name) != nullptr)
    throw CLI::ValidationError(option, "'" + name + "' is traced on the CPU, not a GL method");
  throw CLI::ValidationError(option, "unknown method '" + name + "': use " + method_names());
}

StencilChoice stencil_option(const std::string& stencil, bool zpass, bool zfail) {
  if (zpass && zfail) throw CLI::ValidationError("--zpass", "excludes --zfail");
  std::optional<StencilChoice> alias;
  if (zpass) alias = StencilChoice::zpass;
  if (zfail) alias = StencilChoice::zfail;
  if (stencil.empty()) return alias.value_or(StencilChoice::zfail);
  const std::optional<StencilChoice> choice = parse_stencil_choice(stencil);
  if (!choice) throw CLI::ValidationError("--stencil", "unknown stencil method '" + stencil + "': use auto, zpass or zfail");
  if (alias && *alias != *choice)
    throw CLI::ValidationError(zpass ? "--zpass" : "--zfail", "contradicts --stencil " + stencil);
  return *choice;
}

ShardOption shard_option(const std::string& text, const std::string& option) {
  if (text.empty()) return {};
  // At most 9 digits each: no overflow, and no job array is that large.
  const auto number = [](const std::string& part, std::uint64_t& value) {
    if (part.empty() || part.size() > 9 || part.find_first_not_of("0123456789") != std::string::npos) return false;
    value = std::stoull(part);
    return true;
  };
  ShardOption s;
  const std::size_t slash = text.find('/');
  if (slash == std::string::npos || !number(text.substr(0, slash), s.k) || !number(text.substr(slash + 1), s.n))
    throw CLI::ValidationError(option, "expects K/N (shard K of N, e.g. 2/8), got '" + text + "'");
  if (s.n == 0) throw CLI::ValidationError(option, "N must be at least 1, got '" + text + "'");
  if (s.k == 0 || s.k > s.n)
    throw CLI::ValidationError(option, "K must be in [1, N] (shards are numbered from 1), got '" + text + "'");
  return s;
}

std::vector<gpu::ShadowMethod> shadow_methods_option(const std::string& list, const std::string& option) {
  try {
    return parse_method_list(list);
  } catch (const std::invalid_argument& e) {
    throw CLI::ValidationError(option, e.what());
  }
}

MethodSelection method_selection_option(const std::string& list, const std::string& option) {
  try {
    return parse_method_selection(list);
  } catch (const std::invalid_argument& e) {
    throw CLI::ValidationError(option, e.what());
  }
}

std::unique_ptr<tbb::global_control> thread_limit(unsigned threads, const std::string& option) {
  constexpr unsigned kMaxThreads = 4096;
  if (threads > kMaxThreads)
    throw CLI::ValidationError(option, "at most " + std::to_string(kMaxThreads) + " threads, got " + std::to_string(threads));
  if (threads == 0) return nullptr;
  return std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads);
}

}  // namespace shadowcert::cli
