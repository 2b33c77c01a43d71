// GET /api/runs/{id}/export.html and /api/compare/{group}/export.html
// (server/app/html_export.cpp, routes/export_routes.cpp): one self-contained
// HTML file whose rows decode to the stored frames; the planar demo under
// 3 MB; a cap decimates with a note, or refuses with 413 naming it; unknown
// or malformed ids and caps answer the JSON errors of every route.
#include <gtest/gtest.h>

#include <cstring>
#include <iostream>
#include <string>
#include <vector>

#include "chain_scenario.hpp"
#include "server_fixture.hpp"

namespace rrlab::testing {
namespace {

using nlohmann::json;

constexpr std::size_t kPlanarDemoBound = 3 * 1024 * 1024;

// The server's growth while it streams a 20 MB export. Under AddressSanitizer
// freed memory waits in a quarantine (up to 256 MiB; see frame_export_test.cpp);
// under ThreadSanitizer every allocation also gets shadow memory (2-4 times
// its size: measured 16.6 MiB where the Release build stays under 16), so the
// bound is 4 times the Release one there. The Release build is the check that
// the file is streamed, not buffered.
#if defined(__SANITIZE_ADDRESS__)  // gcc
constexpr long kExportGrowthBoundKib = 256 * 1024;
#elif defined(__SANITIZE_THREAD__)  // gcc
constexpr long kExportGrowthBoundKib = 64 * 1024;
#elif defined(__has_feature)  // clang
#if __has_feature(address_sanitizer)
constexpr long kExportGrowthBoundKib = 256 * 1024;
#elif __has_feature(thread_sanitizer)
constexpr long kExportGrowthBoundKib = 64 * 1024;
#else
constexpr long kExportGrowthBoundKib = 16 * 1024;
#endif
#else
constexpr long kExportGrowthBoundKib = 16 * 1024;
#endif

// The exported file's numbers: RRLAB_EXPORT's header and, per lane, its rows
// decoded from base64 float32.
struct ExportedFile {
  json header;
  std::vector<json> lanes;                 // each lane's metadata
  std::vector<std::vector<float>> values;  // each lane's rows, flat
  std::vector<std::vector<json>> scenes;   // each lane's obstacle keyframes {row, t, obstacles}
};

std::vector<unsigned char> from_base64(const std::string& text) {
  static const std::string alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::vector<unsigned char> out;
  unsigned buffer = 0;
  int bits = 0;
  for (const char c : text) {
    if (c == '=') break;
    const auto at = alphabet.find(c);
    if (at == std::string::npos) throw std::runtime_error("not base64");
    buffer = (buffer << 6) | unsigned(at);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back((buffer >> bits) & 0xff);
    }
  }
  return out;
}

// Read by hand, not with std::regex: a chunk is one line of ~90 KB.
ExportedFile read_export(const std::string& html) {
  ExportedFile file;
  const auto between = [&](std::size_t from, const std::string& open, const std::string& close, std::size_t& end) {
    const std::size_t begin = html.find(open, from);
    if (begin == std::string::npos) return std::string::npos;
    end = html.find(close, begin + open.size());
    if (end == std::string::npos) throw std::runtime_error("unterminated " + open);
    return begin + open.size();
  };
  std::size_t end = 0;
  std::size_t at = between(0, "var RRLAB_EXPORT=", ";\n", end);
  if (at == std::string::npos) throw std::runtime_error("no RRLAB_EXPORT");
  file.header = json::parse(html.substr(at, end - at));
  const std::string lane_open = "RRLAB_EXPORT.lanes.push(", chunk_open = "RRLAB_LANE.chunks.push(\"";
  std::size_t pos = end;
  for (;;) {
    std::size_t lane_end = 0, chunk_end = 0;
    const std::size_t lane = between(pos, lane_open, ");\n", lane_end);
    const std::size_t chunk = between(pos, chunk_open, "\");\n", chunk_end);
    std::size_t scene_end = 0;
    const std::size_t scene = between(pos, "RRLAB_LANE.scenes.push(", ");\n", scene_end);
    if (scene != std::string::npos && scene < std::min(lane, chunk)) {
      file.scenes.back().push_back(json::parse(html.substr(scene, scene_end - scene)));
      pos = scene_end;
      continue;
    }
    if (lane == std::string::npos && chunk == std::string::npos) break;
    if (lane != std::string::npos && (chunk == std::string::npos || lane < chunk)) {
      file.lanes.push_back(json::parse(html.substr(lane, lane_end - lane)));
      file.values.emplace_back();
      file.scenes.emplace_back();
      pos = lane_end;
    } else {
      if (file.values.empty()) throw std::runtime_error("a chunk before any lane");
      const std::vector<unsigned char> bytes = from_base64(html.substr(chunk, chunk_end - chunk));
      const std::size_t n = bytes.size() / 4;
      const std::size_t before = file.values.back().size();
      file.values.back().resize(before + n);
      std::memcpy(file.values.back().data() + before, bytes.data(), n * 4);  // little-endian, as x86 and ARM
      pos = chunk_end;
    }
  }
  return file;
}

class HtmlExport : public ServerTest {
 protected:
  static std::int64_t planar_demo_run() {
    const HttpResult run = send("POST", "/api/runs", {{"scenario", "01_planar7_obstacles"}, {"method", "dls"}, {"mode", "batch"}});
    EXPECT_EQ(run.status, 200) << run.body;
    return run.json().at("id").get<std::int64_t>();
  }
};

TEST_F(HtmlExport, PlanarDemoIsOneSelfContainedFileUnderThreeMegabytesWithEveryFrame) {
  const std::int64_t id = planar_demo_run();
  const HttpResult r = get("/api/runs/" + std::to_string(id) + "/export.html");
  ASSERT_EQ(r.status, 200) << r.body.substr(0, 300);
  EXPECT_EQ(r.content_type, "text/html; charset=utf-8");
  EXPECT_EQ(r.headers.at("content-disposition"), "attachment; filename=\"rrlab-run-" + std::to_string(id) + ".html\"");
  EXPECT_LE(r.body.size(), kPlanarDemoBound);
  std::cout << "planar demo export: " << r.body.size() << " bytes\n";
  EXPECT_EQ(r.body.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_NE(r.body.find("</html>"), std::string::npos);
  EXPECT_NE(r.body.find("<input id=\"scrubber\" type=\"range\""), std::string::npos);
  // nothing loaded from elsewhere: no script files, stylesheets, modules or requests
  for (const char* loads : {"<script src", " src=", "<link", "type=\"module\"", "fetch(", "XMLHttpRequest"})
    EXPECT_EQ(r.body.find(loads), std::string::npos) << loads;

  const ExportedFile file = read_export(r.body);
  EXPECT_TRUE(file.header["note"].is_null());
  EXPECT_EQ(file.header["stride"], 1);
  ASSERT_EQ(file.lanes.size(), 1u);
  const json& lane = file.lanes[0];
  EXPECT_EQ(lane["run"], id);
  EXPECT_EQ(lane["method"], "dls");
  EXPECT_EQ(lane["model"]["dims"], 2);
  EXPECT_EQ(lane["model"]["links"], 7);
  const std::size_t width = lane["row_floats"].get<std::size_t>();
  EXPECT_EQ(width, 5u + 2u + 2u * 2u * 7u);  // scalars, target, 7 links' start and end
  ASSERT_EQ(file.values[0].size(), 800 * width);  // every stored frame
  EXPECT_EQ(file.values[0][0], 0.0f);             // t of the first
  EXPECT_NEAR(file.values[0][799 * width], 7.99, 1e-4);  // and of the last
  // the first link starts at the base
  EXPECT_NEAR(file.values[0][7], lane["model"]["base"][0].get<double>(), 1e-6);
  EXPECT_NEAR(file.values[0][8], lane["model"]["base"][1].get<double>(), 1e-6);
  EXPECT_NE(r.body.find("RRLAB_LANE.scenes.push({\"row\":0,"), std::string::npos);  // the obstacles at the start
}

TEST_F(HtmlExport, ACapDecimatesWithANoteAndKeepsTheLastFrameOrIsRefusedWith413NamingIt) {
  const std::int64_t id = planar_demo_run();
  const std::string path = "/api/runs/" + std::to_string(id) + "/export.html";
  const HttpResult small = get(path + "?max_bytes=60000");
  ASSERT_EQ(small.status, 200) << small.body.substr(0, 300);
  EXPECT_LE(small.body.size(), 60000u);
  const ExportedFile file = read_export(small.body);
  const std::int64_t stride = file.header["stride"].get<std::int64_t>();
  EXPECT_GT(stride, 1);
  EXPECT_NE(file.header["note"].get<std::string>().find("Decimated to fit the cap of 60000 bytes"), std::string::npos);
  const std::size_t width = file.lanes[0]["row_floats"].get<std::size_t>();
  const std::size_t rows = file.values[0].size() / width;
  EXPECT_EQ(rows, std::size_t(799 / stride + 1 + (799 % stride ? 1 : 0)));
  EXPECT_GE(rows, 100u);
  EXPECT_NEAR(file.values[0][(rows - 1) * width], 7.99, 1e-4);  // the last frame kept

  const HttpResult refused = get(path + "?max_bytes=1000");
  ASSERT_EQ(refused.status, 413);
  const json error = error_of(refused);
  EXPECT_EQ(error["code"], "export_too_large");
  EXPECT_EQ(error["path"], "max_bytes");
  EXPECT_EQ(error["allowed"], 1000);
  EXPECT_NE(error["message"].get<std::string>().find("cap of 1000 bytes"), std::string::npos) << error;
}

// 20,000 frames of a 64-link chain (about 45 MB of rows): under the default
// cap of 20 MiB with a note, every lane's last frame kept, and the server
// holding a batch at a time, not the file.
TEST_F(HtmlExport, ARunOverTheDefaultCapIsDecimatedUnderItWithANote) {
  constexpr int kDof = 64, kSteps = 20'000;
  const HttpResult run =
      send("POST", "/api/runs", {{"scenario", chain_scenario("chain_export", kDof, kSteps)}, {"mode", "batch"}});
  ASSERT_EQ(run.status, 200) << run.body;
  const long before = resident_kib(server_->pid());
  const HttpResult r = get("/api/runs/" + std::to_string(run.json().at("id").get<long>()) + "/export.html");
  ASSERT_EQ(r.status, 200) << r.body.substr(0, 300);
  std::cout << "64-link chain, 20,000 frames: " << r.body.size() << " bytes\n";
  EXPECT_LE(r.body.size(), std::size_t(20 * 1024 * 1024));
  EXPECT_GT(r.body.size(), std::size_t(10 * 1024 * 1024));  // the cap used, not a token sample
  const ExportedFile file = read_export(r.body);
  const std::int64_t stride = file.header["stride"].get<std::int64_t>();
  EXPECT_GE(stride, 2);
  EXPECT_NE(file.header["note"].get<std::string>().find("one stored frame in every " + std::to_string(stride)),
            std::string::npos);
  const std::size_t width = file.lanes[0]["row_floats"].get<std::size_t>();
  const std::size_t rows = file.values[0].size() / width;
  EXPECT_EQ(rows, std::size_t((kSteps - 1) / stride + 1 + ((kSteps - 1) % stride ? 1 : 0)));
  EXPECT_NEAR(file.values[0][(rows - 1) * width], (kSteps - 1) * 0.01, 1e-3);  // the last frame
  // streamed: the server did not build the 20 MB file (nor 45 MB of rows) in memory
  EXPECT_LT(resident_kib(server_->pid()) - before, kExportGrowthBoundKib);
}

// An obstacle moved during a live run: the file's obstacles move at that frame.
TEST_F(HtmlExport, RecordedObstacleEditsBecomeKeyframesAtTheirFrame) {
  const std::int64_t id = start_live({{"scenario", "01_planar7_obstacles"}, {"rate", 1}, {"paused", true}});
  const std::string base = "/api/runs/" + std::to_string(id);
  for (int i = 0; i < 3; ++i) ASSERT_EQ(send("POST", base + "/control", {{"action", "step"}}).status, 200);
  ASSERT_EQ(send("PUT", base + "/obstacles/disc", {{"position", {0.2, 1.6}}}).status, 200);
  for (int i = 0; i < 3; ++i) ASSERT_EQ(send("POST", base + "/control", {{"action", "step"}}).status, 200);
  ASSERT_EQ(send("POST", base + "/control", {{"action", "stop"}}).status, 200);
  wait_ended(id);
  const HttpResult r = get(base + "/export.html");
  ASSERT_EQ(r.status, 200) << r.body.substr(0, 300);
  const ExportedFile file = read_export(r.body);
  ASSERT_EQ(file.scenes.size(), 1u);
  ASSERT_EQ(file.scenes[0].size(), 2u) << json(file.scenes[0]);
  EXPECT_EQ(file.scenes[0][0]["row"], 0);
  EXPECT_EQ(file.scenes[0][1]["row"], 3);
  json disc;
  for (const json& o : file.scenes[0][1]["obstacles"])
    if (o["id"] == "disc") disc = o;
  ASSERT_FALSE(disc.is_null());
  EXPECT_NEAR(disc["center"][0].get<double>(), 0.2, 1e-9);
  EXPECT_NEAR(disc["center"][1].get<double>(), 1.6, 1e-9);
}

TEST_F(HtmlExport, UnknownOrMalformedIdsAndCapsAnswerJsonErrors) {
  for (const std::string& path : {"/api/runs/987654/export.html", "/api/runs/abc/export.html",
                                  "/api/compare/987654/export.html", "/api/compare/-1/export.html"}) {
    const HttpResult r = get(path);
    EXPECT_EQ(r.status, 404) << path;
    EXPECT_EQ(error_of(r)["code"], "not_found") << path;
    EXPECT_EQ(error_of(r)["path"], "id") << path;
  }
  const std::int64_t id = planar_demo_run();
  for (const std::string& cap : {"0", "abc", "20971521"}) {
    const HttpResult r = get("/api/runs/" + std::to_string(id) + "/export.html?max_bytes=" + cap);
    EXPECT_EQ(r.status, 400) << cap;
    EXPECT_EQ(error_of(r)["path"], "max_bytes") << cap;
  }
  EXPECT_EQ(http(port(), "POST", "/api/runs/" + std::to_string(id) + "/export.html").status, 405);
}

TEST_F(HtmlExport, ACompareGroupIsOneFileWithEveryLaneInOrder) {
  const HttpResult compare = send("POST", "/api/compare",
                                  {{"scenario", "01_planar7_obstacles"}, {"methods", {"pinv", "dls"}}, {"mode", "batch"}});
  ASSERT_EQ(compare.status, 200) << compare.body;
  const std::int64_t group = compare.json().at("group").get<std::int64_t>();
  const HttpResult r = get("/api/compare/" + std::to_string(group) + "/export.html");
  ASSERT_EQ(r.status, 200) << r.body.substr(0, 300);
  EXPECT_EQ(r.headers.at("content-disposition"), "attachment; filename=\"rrlab-compare-" + std::to_string(group) + ".html\"");
  const ExportedFile file = read_export(r.body);
  ASSERT_EQ(file.lanes.size(), 2u);
  EXPECT_EQ(file.lanes[0]["method"], "pinv");
  EXPECT_EQ(file.lanes[1]["method"], "dls");
  EXPECT_EQ(file.lanes[0]["run"], group);
  for (std::size_t i = 0; i < 2; ++i)
    EXPECT_EQ(file.values[i].size(), 800 * file.lanes[i]["row_floats"].get<std::size_t>()) << i;

  // the second lane's run id is not a group: the error says which group it is in
  const std::int64_t second = file.lanes[1]["run"].get<std::int64_t>();
  const HttpResult other = get("/api/compare/" + std::to_string(second) + "/export.html");
  EXPECT_EQ(other.status, 404);
  EXPECT_NE(error_of(other)["message"].get<std::string>().find("is in compare group " + std::to_string(group)),
            std::string::npos)
      << other.body;
}

}  // namespace
}  // namespace rrlab::testing
