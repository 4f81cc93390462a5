// libFuzzer harness: the reader of certify's --points files (io/point_file.h), on
// arbitrary bytes (docs/fuzzing-parsers.md).
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/input_error.h"
#include "fuzz/fuzz_check.h"
#include "io/point_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using shadowcert::fuzz::require;
  const std::string file_name = "fuzz.txt";
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const std::vector<shadowcert::Vec3> points = shadowcert::parse_point_file(text, file_name);
    for (const shadowcert::Vec3& p : points) require(shadowcert::fuzz::finite(p));
  } catch (const shadowcert::InputError& error) {
    require(error.file() == file_name);
  }
  return 0;
}
