// Static files of web/ (the dashboard and its npm packages under
// web/node_modules): a request path maps to a file inside the web root or to
// nothing (404), never outside it (no "..", no symlink escape). Answers carry
// Cache-Control: no-cache and an ETag, so a browser revalidates every load
// and gets 304 for what has not changed (edits show at once, three.js is not
// downloaded again). Every answer carries the security headers below.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace rrlab::server {

struct StaticFile {
  std::string path;       // absolute, inside the root
  std::string mime_type;
  std::string etag;  // "size-mtime" (hex), quoted as HTTP wants it
};

inline constexpr const char* kStaticCacheControl = "no-cache";

// Content-Security-Policy: scripts, styles, connections and everything else
// from this server only; no inline script and no inline style. The one
// exception is an HTML page's inline import map (<script type="importmap">,
// which browsers cannot load from a file): it is allowed by its SHA-256
// hash, so the page can map bare module names but not run inline code.
// `html`: the page's text (empty for other files).
std::string content_security_policy(std::string_view html);
// The security headers of a static answer: that policy, nosniff, no framing, no referrer.
std::vector<std::pair<std::string, std::string>> static_security_headers(std::string_view html);

std::optional<StaticFile> resolve_static(const std::string& web_root, std::string_view request_path);
std::string mime_type(std::string_view path);

}  // namespace rrlab::server
