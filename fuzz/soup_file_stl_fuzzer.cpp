// libFuzzer harness: read_soup's reader of .stl files, on arbitrary bytes (docs/fuzzing-parsers.md).
#include <cstddef>
#include <cstdint>

#include "fuzz/soup_file_fuzz.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return shadowcert::fuzz::fuzz_soup_file(data, size, "fuzz.stl");
}
