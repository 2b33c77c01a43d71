// GET /api/runs/{id}/export.html and /api/compare/{group}/export.html: one
// self-contained HTML file that replays stored runs offline (no network, no
// ES modules: the viewer of html_viewer.html, its script inlined). Streamed
// like a frame export (a BodyStream produced on an export worker): the
// viewer's page, then each lane's metadata, then its frames a batch at a time
// (each batch from its own short query, as base64 of little-endian float32
// rows), then the lane's obstacle keyframes, then the viewer's script. Memory
// is one batch per lane being written, whatever the run's length.
//
// Size: the file is estimated before the first byte (the rows have a fixed
// width) and kept under `max_bytes` (at most kHtmlExportCap) by keeping every
// stride-th stored frame (and the last), the same stride for every lane, with
// a note in the file; when even kHtmlExportMinFrames frames per lane do not fit,
// make_html_export refuses with Problem::too_large naming the cap.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <rrlab/server/api/response.hpp>
#include <rrlab/storage/run_store.hpp>

namespace rrlab::server {

inline constexpr std::int64_t kHtmlExportCap = 20 * 1024 * 1024;  // bytes: the largest file answered
inline constexpr std::int64_t kHtmlExportMinFrames = 100;         // per lane, fewer only when stored so

// The stream of the file for `lanes` (one run, or a compare group's runs in
// lane order). Throws DomainError: wrong_state when a run has no stored
// frames or its scenario no longer loads; too_large (413) when it cannot fit
// `max_bytes`. `title` heads the page ("run 12", "compare 40").
std::shared_ptr<BodyStream> make_html_export(storage::RunStore& store, const std::vector<storage::RunRecord>& lanes,
                                             const std::string& title, std::int64_t max_bytes);

// The viewer page (html_viewer.html, compiled in): the part before the data
// and the part after it.
const std::string& html_viewer_head();
const std::string& html_viewer_tail();

}  // namespace rrlab::server
