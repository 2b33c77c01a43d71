#include <rrlab/server/net/static_files.hpp>

#include <cstdio>
#include <filesystem>

#include <rrlab/server/net/sha256.hpp>

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

std::string content_security_policy(std::string_view html) {
  std::string scripts = "'self'";
  constexpr std::string_view kOpen = "<script type=\"importmap\">", kClose = "</script>";
  for (auto open = html.find(kOpen); open != std::string_view::npos; open = html.find(kOpen, open + 1)) {
    const auto begin = open + kOpen.size();
    const auto end = html.find(kClose, begin);
    if (end == std::string_view::npos) break;
    const auto digest = sha256(html.substr(begin, end - begin));
    scripts += " 'sha256-" + base64(digest.data(), digest.size()) + "'";
  }
  return "default-src 'self'; script-src " + scripts +
         "; style-src 'self'; img-src 'self' data: blob:; connect-src 'self'; object-src 'none'; base-uri 'none'; "
         "form-action 'self'; frame-ancestors 'none'";
}

std::vector<std::pair<std::string, std::string>> static_security_headers(std::string_view html) {
  return {{"Content-Security-Policy", content_security_policy(html)},
          {"X-Content-Type-Options", "nosniff"},
          {"X-Frame-Options", "DENY"},
          {"Referrer-Policy", "no-referrer"}};
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
