#include "net/static_files.hpp"

#include <cstdio>
#include <filesystem>

namespace rrlab::server {

namespace fs = std::filesystem;

std::string mime_type(std::string_view path) {
  const auto dot = path.rfind('.');
  const std::string_view ext = dot == std::string_view::npos ? "" : path.substr(dot);
  if (ext == ".html" || ext == ".htm") return "text/html; charset=utf-8";
  if (ext == ".js" || ext == ".mjs") return "text/javascript; charset=utf-8";
  if (ext == ".css") return "text/css; charset=utf-8";
  if (ext == ".json" || ext == ".map") return "application/json";
  if (ext == ".svg") return "image/svg+xml";
  if (ext == ".png") return "image/png";
  if (ext == ".jpg" || ext == ".jpeg") return "image/jpeg";
  if (ext == ".ico") return "image/x-icon";
  if (ext == ".wasm") return "application/wasm";
  if (ext == ".txt" || ext == ".md") return "text/plain; charset=utf-8";
  return "application/octet-stream";
}

std::optional<StaticFile> resolve_static(const std::string& web_root, std::string_view request_path) {
  if (web_root.empty() || request_path.empty() || request_path.front() != '/') return std::nullopt;
  // percent-encoded and backslash tricks are refused outright
  if (request_path.find('%') != std::string_view::npos || request_path.find('\\') != std::string_view::npos ||
      request_path.find('\0') != std::string_view::npos)
    return std::nullopt;
  std::string relative(request_path.substr(1));
  if (relative.empty() || relative.back() == '/') relative += "index.html";
  const fs::path rel(relative);
  for (const auto& part : rel)
    if (part == ".." || part == ".") return std::nullopt;
  std::error_code ec;
  const fs::path root = fs::canonical(web_root, ec);
  if (ec) return std::nullopt;
  const fs::path file = fs::canonical(root / rel, ec);
  if (ec || !fs::is_regular_file(file, ec)) return std::nullopt;
  // the resolved file (after symlinks) must still be under the root
  const auto [root_end, file_it] = std::mismatch(root.begin(), root.end(), file.begin(), file.end());
  if (root_end != root.end()) return std::nullopt;
  const auto size = fs::file_size(file, ec);
  if (ec) return std::nullopt;
  const auto modified = fs::last_write_time(file, ec).time_since_epoch().count();
  if (ec) return std::nullopt;
  char etag[64];
  std::snprintf(etag, sizeof etag, "\"%llx-%llx\"", static_cast<unsigned long long>(size),
                static_cast<unsigned long long>(modified));
  return StaticFile{file.string(), mime_type(file.string()), etag};
}

}  // namespace rrlab::server
