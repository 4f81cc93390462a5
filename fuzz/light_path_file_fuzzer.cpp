// libFuzzer harness: the reader of track's --path files (io/light_path_file.h), on arbitrary
// bytes (docs/fuzzing-parsers.md).
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/input_error.h"
#include "core/light.h"
#include "fuzz/fuzz_check.h"
#include "io/light_path_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using shadowcert::fuzz::require;
  const std::string file_name = "fuzz.txt";
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const std::vector<shadowcert::Light> lights = shadowcert::parse_light_path_file(text, file_name);
    require(!lights.empty());
    for (const shadowcert::Light& light : lights) require(light.defined());
  } catch (const shadowcert::InputError& error) {
    require(error.file() == file_name);
  }
  return 0;
}
