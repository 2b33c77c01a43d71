// External methods (the Python package's): found by name once registered, by
// scenarios too; built-in names refused; a stored scenario whose Python
// method this process lacks says so.
#include <rrlab/methods/registry.hpp>

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include <rrlab/scenario/scenario.hpp>

#include "engine/test_models.hpp"

namespace rrlab {
namespace {

nlohmann::json registry_test_scenario(const nlohmann::json& method) {
  return {{"dt", 0.01},
          {"duration", 0.1},
          {"robot", test::planar_robot(3, 0.5, 0.02, {0.3, 0.3, 0.3})},
          {"task", {{"space", "xy"}, {"trajectory", {{"type", "circle"}, {"center", {0.9, 0.5}}, {"radius", 0.1}}}}},
          {"method", method}};
}

TEST(MethodRegistry, AnExternalMethodIsFoundByNameOnceRegistered) {
  EXPECT_EQ(find_method("registry_test_method"), nullptr);
  MethodInfo info;
  info.name = "registry_test_method";
  info.params = {{"gain", "Gain", "", "", 1.0, 0.0, 2.0, 0.1, {}}};
  info.make = [](const MethodContext& ctx) { return find_method("pinv")->make(ctx); };
  info.python = true;
  MethodInfo costless = info;  // a row without a step cost does not register
  EXPECT_THROW(register_external_method(costless), std::invalid_argument);
  EXPECT_EQ(find_method("registry_test_method"), nullptr);
  info.step_cost = unit_step_cost;
  register_external_method(info);
  const MethodInfo* found = find_method("registry_test_method");
  ASSERT_NE(found, nullptr);
  EXPECT_TRUE(found->python);
  EXPECT_NE(method_names().find("registry_test_method (Python)"), std::string::npos);
  // scenarios name it, with its parameters checked against its specs
  const Scenario sc = parse_scenario(registry_test_scenario({{"name", "registry_test_method"}, {"params", {{"gain", 1.5}}}}));
  EXPECT_EQ(sc.method.name, "registry_test_method");
  EXPECT_THROW(parse_scenario(registry_test_scenario({{"name", "registry_test_method"}, {"params", {{"gain", 3}}}})),
               ScenarioError);
  // registering again replaces it for later lookups; the earlier entry stays valid
  info.params.clear();
  register_external_method(info);
  EXPECT_TRUE(find_method("registry_test_method")->params.empty());
  EXPECT_EQ(found->params.size(), 1u);
  info.name = "pinv";
  EXPECT_THROW(register_external_method(info), std::invalid_argument);
}

// Each built-in row names its section of docs/methods.md, and the section and its anchor are there.
TEST(MethodRegistry, EveryBuiltInMethodHasAStepCostAndItsDocumentation) {
  std::ifstream file(test::source_path("docs/methods.md"));
  std::stringstream text;
  text << file.rdbuf();
  for (const MethodInfo& info : method_registry()) {
    EXPECT_NE(info.step_cost, nullptr) << info.name;
    const std::string prefix = "docs/methods.md#";
    ASSERT_EQ(info.docs.rfind(prefix, 0), 0u) << info.name << ": " << info.docs;
    EXPECT_EQ(info.docs.substr(prefix.size()), info.name);
    // the anchor is real: an id right above the method's section
    EXPECT_NE(text.str().find("<a id=\"" + info.name + "\"></a>\n\n## `" + info.name + "`"), std::string::npos)
        << "no anchored section for " << info.name;
  }
}

TEST(MethodRegistry, AStoredPythonMethodThisProcessLacksIsNamedAsSuch) {
  try {
    parse_scenario(registry_test_scenario({{"name", "nobody_registered_me"}, {"origin", "python"}}));
    FAIL() << "no error";
  } catch (const ScenarioError& e) {
    EXPECT_EQ(e.path(), "method.name");
    EXPECT_NE(std::string(e.what()).find("is a method written in Python"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parse_scenario(registry_test_scenario({{"name", "pinv"}, {"origin", "fortran"}})), ScenarioError);
  EXPECT_THROW(parse_scenario(registry_test_scenario({{"name", "pinv"}, {"origin", "python"}})), ScenarioError);
  EXPECT_NO_THROW(parse_scenario(registry_test_scenario({{"name", "pinv"}})));
}

}  // namespace
}  // namespace rrlab
