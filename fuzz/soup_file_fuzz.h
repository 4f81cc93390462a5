#pragma once
// The body the four soup-file harnesses share (soup_file_{obj,off,ply,stl}_fuzzer.cpp): one
// harness per format, so that each corpus and dictionary stays within one grammar.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "core/input_error.h"
#include "io/soup_file.h"
#include "fuzz/fuzz_check.h"

namespace shadowcert::fuzz {

// Reads the bytes as a file named `file_name` (its extension picks the format). Any input
// must give a soup or an InputError: another exception escapes and libFuzzer reports it.
inline int fuzz_soup_file(const std::uint8_t* data, std::size_t size, const std::string& file_name) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  try {
    const Soup soup = parse_soup(bytes, file_name);
    require_valid_soup(soup);
    // read_soup refuses a file without a face, and every face has at least three corners.
    require(!soup.triangles.empty());
  } catch (const InputError& error) {
    // The message must name the file, whatever the input (core/input_error.h).
    require(error.file() == file_name);
  }
  return 0;
}

}  // namespace shadowcert::fuzz
