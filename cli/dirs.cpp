#include <filesystem>
#include <iostream>

#include "cli.hpp"

namespace rrlab::cli {

std::string find_dir(const std::optional<std::string>& given, const char* name) {
  if (given) return *given;
  std::error_code ec;
  if (std::filesystem::is_directory(name, ec)) return name;
  const std::string source = std::string(RRLAB_SOURCE_DIR) + "/" + name;
  if (std::filesystem::is_directory(source, ec)) return source;
  return name;
}

bool database_exists(const std::string& db) {
  std::error_code ec;
  if (std::filesystem::is_regular_file(db, ec)) return true;
  std::cerr << "rrlab: error: no database file '" << db << "'\n";
  return false;
}

}  // namespace rrlab::cli
