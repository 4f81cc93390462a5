#include "cli/image_size.h"

#include <cstddef>
#include <stdexcept>

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
  constexpr unsigned long kMaxSide = 16384;  // GL_MAX_RENDERBUFFER_SIZE of every driver we target
  if (w == 0 || h == 0 || w > kMaxSide || h > kMaxSide)
    throw CLI::ValidationError(option, "each side must be in [1, 16384]");
  camera.width = static_cast<std::uint32_t>(w);
  camera.height = static_cast<std::uint32_t>(h);
}

}  // namespace shadowcert::cli
