// Output files of the CLI: folders made on demand, JSON written pretty-printed.
#pragma once
#include <filesystem>
#include <string_view>
#include <nlohmann/json.hpp>

namespace shadowcert {

// Creates the folders above `file` (nothing for a bare name); throws InputError naming the
// file when that fails. Every output option of the CLI calls it before writing.
void create_parent_directories(const std::filesystem::path& file);

// Writes `value` pretty-printed to `file`, creating parent folders; throws InputError
// naming the file when it cannot be written.
void write_json_file(const std::filesystem::path& file, const nlohmann::json& value);

// Writes `text` as it is to `file`, creating parent folders; throws InputError naming the file
// when it cannot be written.
void write_text_file(const std::filesystem::path& file, std::string_view text);

}  // namespace shadowcert
