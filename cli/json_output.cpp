#include "cli/json_output.h"

#include <fstream>
#include <system_error>

#include "core/input_error.h"

namespace shadowcert::cli {

void write_json_file(const std::filesystem::path& file, const nlohmann::json& value) {
  std::error_code ec;
  if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path(), ec);
  std::ofstream out(file);
  if (!out) throw InputError(file.string(), "cannot open for writing");
  out << value.dump(2) << '\n';
  if (!out) throw InputError(file.string(), "write failed");
}

}  // namespace shadowcert::cli
