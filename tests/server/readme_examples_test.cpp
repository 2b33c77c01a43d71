// The REST examples of docs/api.md (the fenced block between <!-- api-examples -->
// and <!-- /api-examples -->; the README's curl lines are taken from it) run as
// written against a fresh server.
#include <fstream>
#include <sstream>

#include "server_fixture.hpp"

namespace rrlab::testing {
namespace {

class ApiDocExamples : public ServerTest {};

TEST_F(ApiDocExamples, CurlBlockRunsAsWritten) {
  std::ifstream in(std::string(RRLAB_SOURCE_DIR) + "/docs/api.md");
  std::stringstream text;
  text << in.rdbuf();
  const std::string doc = text.str();
  const auto start = doc.find("<!-- api-examples -->");
  const auto end = doc.find("<!-- /api-examples -->");
  ASSERT_NE(start, std::string::npos);
  ASSERT_NE(end, std::string::npos);
  std::string block = doc.substr(start, end - start);
  block = block.substr(block.find("```sh") + 5);
  block = block.substr(0, block.rfind("```"));
  const std::string script = temp_dir() + "/examples.sh";
  std::ofstream(script) << "set -euo pipefail\n" << block;
  const std::string command = "RRLAB=http://127.0.0.1:" + std::to_string(port()) + " bash " + script + " > " + script +
                              ".out 2>&1";
  const int status = std::system(command.c_str());
  std::ifstream out(script + ".out");
  std::stringstream output;
  output << out.rdbuf();
  EXPECT_EQ(status, 0) << output.str();
  EXPECT_NE(output.str().find("\"identical\":true"), std::string::npos) << output.str();
}

}  // namespace
}  // namespace rrlab::testing
