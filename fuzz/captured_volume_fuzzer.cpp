// libFuzzer harness: the .vol reader of captured shadow volumes (io/volume_file.h),
// on arbitrary bytes, then the weld (scene/welded_volume.h) that certify --volume runs on what it read
// (docs/fuzzing-parsers.md).
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "core/input_error.h"
#include "io/volume_file.h"
#include "scene/welded_volume.h"
#include "fuzz/fuzz_check.h"

namespace {

using shadowcert::fuzz::require;

// read_volume_file's promise: finite coordinates, w in {0, 1}, indices in range.
void require_valid_volume(const shadowcert::HomogeneousMesh& volume) {
  for (const std::array<float, 4>& v : volume.vertices) {
    for (const float c : v) require(std::isfinite(c));
    require(v[3] == 0.0f || v[3] == 1.0f);
  }
  for (const auto& t : volume.triangles)
    for (const std::uint32_t index : t) require(index < volume.vertices.size());
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string file_name = "fuzz.vol";
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const shadowcert::HomogeneousMesh volume = shadowcert::parse_volume_file(text, file_name);
    require_valid_volume(volume);
    // Welding keeps every triangle and never adds a vertex.
    const shadowcert::HomogeneousMesh welded = shadowcert::weld_volume(volume);
    require_valid_volume(welded);
    require(welded.triangles.size() == volume.triangles.size());
    require(welded.vertices.size() <= volume.vertices.size());
  } catch (const shadowcert::InputError& error) {
    require(error.file() == file_name);
  }
  return 0;
}
