// Method's parameter slots: a method reads its parameters by name, so a name
// its spec list lacks fails when the method is built, never a silent read of
// another parameter's value.
#include <rrlab/methods/method.hpp>

#include <gtest/gtest.h>

#include <rrlab/methods/registry.hpp>

#include "engine/test_models.hpp"

namespace rrlab {
namespace {

std::vector<ParamSpec> two_params() {
  return {{"gain", "Gain", "", "", 2.0, 0.0, 10.0, 0.1, {}},
          {"mode", "Mode", "", "", 1, 0, 1, 1, {"slow", "fast"}}};
}

// A method that reads the parameters it is told to, by name.
class Probe final : public Method {
 public:
  explicit Probe(const char* param, const char* mode_label = "fast")
      : Method(two_params()), read_(slot(param)), fast_(label(slot("mode"), mode_label)) {}
  void step(const StepInput&, StepOutput&) override {}
  double value() const { return p(read_); }
  int fast() const { return fast_; }
  ParamSlot last_changed;

 protected:
  void on_param_changed(ParamSlot changed) override { last_changed = changed; }

 private:
  ParamSlot read_;
  int fast_;
};

TEST(MethodParams, ASlotReadsItsOwnParameterWhereverItSits) {
  Probe gain("gain"), mode("mode");
  EXPECT_EQ(gain.value(), 2.0);
  EXPECT_EQ(mode.value(), 1.0);
  EXPECT_EQ(gain.fast(), 1);
  gain.set_param("gain", 7.5);
  EXPECT_EQ(gain.value(), 7.5);
  EXPECT_EQ(gain.last_changed, ParamSlot{0});
}

TEST(MethodParams, AnUndeclaredParameterOrLabelFailsWhenTheMethodIsBuilt) {
  try {
    Probe bad("lambda");
    FAIL() << "built a method that reads an undeclared parameter";
  } catch (const std::logic_error& e) {
    EXPECT_NE(std::string(e.what()).find("'lambda'"), std::string::npos) << e.what();
  }
  try {
    Probe bad("gain", "medium");
    FAIL() << "built a method that compares with an undeclared label";
  } catch (const std::logic_error& e) {
    EXPECT_NE(std::string(e.what()).find("'medium'"), std::string::npos) << e.what();
  }
}

// Every registered method builds on planar and spatial arms: each slot and
// label it reads is in its spec list.
TEST(MethodParams, EveryRegisteredMethodFindsEveryParameterItReads) {
  for (const ModelKind kind : {ModelKind::planar, ModelKind::dh}) {
    const Model model = test::random_model(kind, 7, 3);
    const TaskSpace space = kind == ModelKind::planar ? TaskSpace::xy : TaskSpace::pose;
    for (const MethodInfo& info : method_registry()) {
      SCOPED_TRACE(info.name);
      std::unique_ptr<Method> method;
      EXPECT_NO_THROW(method = info.make(MethodContext{model, space, 2}));
      if (method) {
        EXPECT_EQ(method->param_values().size(), Eigen::Index(info.params.size()));
      }
    }
  }
}

}  // namespace
}  // namespace rrlab
