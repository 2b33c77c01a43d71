#include <filesystem>

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

}  // namespace rrlab::cli
