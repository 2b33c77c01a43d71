// Static files of web/: a request path maps to a file inside the web root or
// to nothing (404), never outside it (no "..", no symlink escape).
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace rrlab::server {

struct StaticFile {
  std::string path;       // absolute, inside the root
  std::string mime_type;
};

std::optional<StaticFile> resolve_static(const std::string& web_root, std::string_view request_path);
std::string mime_type(std::string_view path);

}  // namespace rrlab::server
