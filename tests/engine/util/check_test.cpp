#include <rrlab/util/check.hpp>

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace rrlab {
namespace {

int checked_half(int even) {
  RRLAB_CHECK(even % 2 == 0, "not even: " + std::to_string(even));
  return even / 2;
}

// RRLAB_CHECK throws std::invalid_argument naming the function, the message
// and the condition, in every build: the tests run in Release (NDEBUG), where
// an assert() would have let the odd number through.
TEST(Check, ThrowsInvalidArgumentWithTheMessageAndTheConditionInEveryBuild) {
  EXPECT_EQ(checked_half(4), 2);
  try {
    checked_half(3);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("checked_half"), std::string::npos) << what;
    EXPECT_NE(what.find("not even: 3"), std::string::npos) << what;
    EXPECT_NE(what.find("even % 2 == 0"), std::string::npos) << what;
  }
}

// The message is built only when the check fails.
TEST(Check, BuildsTheMessageOnlyOnFailure) {
  int built = 0;
  const auto message = [&] {
    ++built;
    return std::string("built");
  };
  RRLAB_CHECK(true, message());
  EXPECT_EQ(built, 0);
  EXPECT_THROW(RRLAB_CHECK(false, message()), std::invalid_argument);
  EXPECT_EQ(built, 1);
}

}  // namespace
}  // namespace rrlab
