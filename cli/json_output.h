#pragma once
#include <filesystem>
#include <nlohmann/json.hpp>

namespace shadowcert::cli {

// Writes `value` pretty-printed to `file`, creating parent folders; throws InputError
// naming the file when it cannot be written.
void write_json_file(const std::filesystem::path& file, const nlohmann::json& value);

}  // namespace shadowcert::cli
