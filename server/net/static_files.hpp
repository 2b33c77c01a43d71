// Static files of web/ (the dashboard and its npm packages under
// web/node_modules): a request path maps to a file inside the web root or to
// nothing (404), never outside it (no "..", no symlink escape). Answers carry
// Cache-Control: no-cache and an ETag, so a browser revalidates every load
// and gets 304 for what has not changed (edits show at once, three.js is not
// downloaded again).
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace rrlab::server {

struct StaticFile {
  std::string path;       // absolute, inside the root
  std::string mime_type;
  std::string etag;  // "size-mtime" (hex), quoted as HTTP wants it
};

inline constexpr const char* kStaticCacheControl = "no-cache";

std::optional<StaticFile> resolve_static(const std::string& web_root, std::string_view request_path);
std::string mime_type(std::string_view path);

}  // namespace rrlab::server
