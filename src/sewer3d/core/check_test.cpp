#include "sewer3d/core/check.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace sewer3d {
namespace {

bool Contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(Check, InternalInvariantNamesConditionAndSourceLocation) {
  try {
    const int n = -1;
    SEWER3D_CHECK(n > 0, "n = " << n);
    FAIL() << "no throw";
  } catch (const std::invalid_argument&) {
    FAIL() << "an internal error must not pass for a caller's bad value";
  } catch (const InternalError& e) {
    EXPECT_TRUE(Contains(e.what(), "n > 0")) << e.what();
    EXPECT_TRUE(Contains(e.what(), "n = -1")) << e.what();
    EXPECT_TRUE(Contains(e.what(), "check_test.cpp:")) << e.what();
  }
  EXPECT_NO_THROW(SEWER3D_CHECK(true));
}

TEST(Check, ValidationSpeaksInTheCallersTerms) {
  const double speed_mm_s = -5.0;
  try {
    SEWER3D_VALIDATE(speed_mm_s > 0.0, "speed_mm_s", "must be > 0, got " << speed_mm_s);
    FAIL() << "no throw";
  } catch (const InvalidValue& e) {
    EXPECT_EQ(std::string(e.what()), "speed_mm_s: must be > 0, got -5");
    EXPECT_EQ(e.field(), "speed_mm_s");
    EXPECT_EQ(e.problem(), "must be > 0, got -5");
  }
  EXPECT_THROW(SEWER3D_VALIDATE(false, "x", "bad"), std::invalid_argument);
  EXPECT_NO_THROW(SEWER3D_VALIDATE(true, "x", "bad"));
  EXPECT_STREQ(InvalidValue("", "too few views").what(), "too few views");
}

TEST(Check, CheckWithinPrefixesTheField) {
  try {
    CheckWithin("motion.", [] { throw InvalidValue("speed_mm_s", "must be > 0, got -5"); });
    FAIL() << "no throw";
  } catch (const InvalidValue& e) {
    EXPECT_EQ(std::string(e.what()), "motion.speed_mm_s: must be > 0, got -5");
  }
  // Nested: a scenario's pipe's section.
  try {
    CheckWithin("pipe.", [] {
      CheckWithin("sections[1].", [] { throw InvalidValue("length_mm", "must be > 0, got 0"); });
    });
    FAIL() << "no throw";
  } catch (const InvalidValue& e) {
    EXPECT_EQ(e.field(), "pipe.sections[1].length_mm");
  }
  // A problem of the whole member is named by the member.
  try {
    CheckWithin("pipe.", [] { throw InvalidValue("", "the pipe has no sections"); });
    FAIL() << "no throw";
  } catch (const InvalidValue& e) {
    EXPECT_EQ(std::string(e.what()), "pipe: the pipe has no sections");
  }
  // Internal errors pass through unchanged.
  EXPECT_THROW(CheckWithin("pipe.", [] { SEWER3D_CHECK(false); }), InternalError);
  EXPECT_NO_THROW(CheckWithin("pipe.", [] {}));
}

}  // namespace
}  // namespace sewer3d
