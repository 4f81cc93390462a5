#include "io/output_file.h"

#include <fstream>
#include <system_error>

#include "core/input_error.h"

namespace shadowcert {

void create_parent_directories(const std::filesystem::path& file) {
  if (!file.has_parent_path()) return;
  std::error_code ec;
  std::filesystem::create_directories(file.parent_path(), ec);
  if (ec) throw InputError(file.string(), "cannot create its folder: " + ec.message());
}

void write_json_file(const std::filesystem::path& file, const nlohmann::json& value) {
  create_parent_directories(file);
  std::ofstream out(file);
  if (!out) throw InputError(file.string(), "cannot open for writing");
  out << value.dump(2) << '\n';
  if (!out) throw InputError(file.string(), "write failed");
}

void write_text_file(const std::filesystem::path& file, std::string_view text) {
  create_parent_directories(file);
  std::ofstream out(file);
  if (!out) throw InputError(file.string(), "cannot open for writing");
  out << text;
  if (!out) throw InputError(file.string(), "write failed");
}

}  // namespace shadowcert
