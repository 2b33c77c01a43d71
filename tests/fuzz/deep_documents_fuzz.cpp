// Structured fuzzing of deep and wide documents. The other targets mutate
// short inputs and never reach the depths that overflow a recursive parser
// (60,000 levels of JSON, 140,000 nested XML elements): here the bytes are a
// small program that builds such a document, so a few bytes reach any depth.
//
// byte 0 picks where the document goes: 0-3 a REST body (runs, validate,
// compare, sweeps), 4 a WebSocket message to a live run, 5 the scenario
// parser, 6 an inline URDF in a scenario (the document is XML then). Then
// pairs (op, n) append to the document:
//   JSON: 0 open 256n+1 objects, 1 open 256n+1 arrays, 2 add 64n+1 values,
//         3 close n+1 levels, 4 a string of n brackets, 5 the raw byte n
//   XML:  0 open 256n+1 elements, 1 open one whose attributes hold `<` and
//         `>`, 2 add 64n+1 empty siblings, 3 close n+1 levels, 4 a comment
//         and a CDATA section full of tags, 5 the raw byte n
// and whatever is left open is closed at the end. Documents stop growing at
// 1.5 MB (above the server's 1 MiB body limit).
#include <string>
#include <vector>

#include <rrlab/scenario/scenario.hpp>

#include "fuzz_support.hpp"

namespace {

constexpr std::size_t kMaxDocument = 1536 * 1024;

class JsonBuilder {
 public:
  void apply(std::uint8_t op, std::uint8_t n) {
    switch (op % 6) {
      case 0: for (int i = 0; i <= 256 * n; ++i) open('{'); break;
      case 1: for (int i = 0; i <= 256 * n; ++i) open('['); break;
      case 2: for (int i = 0; i <= 64 * n; ++i) value("1"); break;
      case 3: for (int i = 0; i <= n; ++i) close(); break;
      case 4: value("\"" + std::string(n, '[') + std::string(n / 2, '{') + "\\\"]\""); break;
      case 5: text_ += char(n); break;
    }
  }
  std::string finish() {
    while (!open_.empty()) close();
    if (text_.empty()) text_ = "{}";
    return std::move(text_);
  }
  std::size_t size() const { return text_.size(); }

 private:
  struct Level {
    char bracket;
    bool has_member = false;
  };
  // A comma and, in an object, a key before the next member.
  void member() {
    if (open_.empty()) return;
    Level& top = open_.back();
    if (top.has_member) text_ += ',';
    if (top.bracket == '{') text_ += "\"k\":";
    top.has_member = true;
  }
  void value(const std::string& v) {
    member();
    text_ += v;
  }
  void open(char bracket) {
    member();
    text_ += bracket;
    open_.push_back({bracket});
  }
  void close() {
    if (open_.empty()) return;
    text_ += open_.back().bracket == '{' ? '}' : ']';
    open_.pop_back();
  }
  std::string text_;
  std::vector<Level> open_;
};

class XmlBuilder {
 public:
  XmlBuilder() { text_ = "<robot name=\"r\">"; }
  void apply(std::uint8_t op, std::uint8_t n) {
    switch (op % 6) {
      case 0: for (int i = 0; i <= 256 * n; ++i) open("<link>"); break;
      case 1: open("<joint name=\"a>b\" type='<c>'>"); break;
      case 2: for (int i = 0; i <= 64 * n; ++i) text_ += "<link name=\"l\"/>"; break;
      case 3: for (int i = 0; i <= n && open_ > 0; ++i, --open_) text_ += "</x>"; break;
      case 4: text_ += "<!-- <a><a><a> --><![CDATA[<b><b><b>]]>"; break;
      case 5: text_ += char(n); break;
    }
  }
  std::string finish() {
    for (; open_ > 0; --open_) text_ += "</x>";  // mismatched names: TinyXML refuses, after the depth check
    return text_ + "</robot>";
  }
  std::size_t size() const { return text_.size(); }

 private:
  void open(const char* tag) {
    text_ += tag;
    ++open_;
  }
  std::string text_;
  long open_ = 0;
};

template <typename Builder>
std::string build(const std::uint8_t* data, std::size_t size) {
  Builder b;
  for (std::size_t i = 1; i + 1 < size && b.size() < kMaxDocument; i += 2) b.apply(data[i], data[i + 1]);
  return b.finish();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const int sink = data[0] % 7;
  auto& server = rrlab::fuzz::Server::get();
  if (sink == 6) {
    const std::string xml = build<XmlBuilder>(data, size);
    const nlohmann::json scenario = {{"name", "deep"},
                                      {"dt", 0.01},
                                      {"duration", 1},
                                      {"robot", {{"kind", "urdf"}, {"urdf", xml}, {"link_radius", 0.05}}},
                                      {"task", {{"space", "xyz"}, {"trajectory", {{"type", "joystick"}}}}}};
    rrlab::fuzz::expect_documented("inline URDF", [&] { rrlab::parse_scenario(scenario); });
    return 0;
  }
  const std::string doc = build<JsonBuilder>(data, size);
  static const char* const kRoutes[] = {"/api/runs", "/api/scenarios/validate", "/api/compare", "/api/sweeps"};
  if (sink < 4) {
    server.idle_call("POST", kRoutes[sink], doc);
  } else if (sink == 4) {
    server.live_message(doc);
  } else {
    rrlab::fuzz::expect_documented("parse_scenario_text", [&] { rrlab::parse_scenario_text(doc); });
  }
  return 0;
}
