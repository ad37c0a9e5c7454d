#include "sewer3d/pattern/submap_search.hpp"

#include <gtest/gtest.h>

#include <string>

#include "sewer3d/pattern/default_pattern.hpp"

namespace sewer3d {
namespace {

TEST(SubmapSearch, ReachesSmallTorusAndVerifies) {
  SubmapSearchOptions options;
  options.rows = 6;
  options.cols = 60;
  options.seed = 11;
  const SubmapSearchResult result = SearchPerfectSubmap(options);
  ASSERT_TRUE(result.reached) << result.termination;
  EXPECT_EQ(result.final_cost, 0);
  const PatternReport report = VerifyPattern(result.array, options.constraints);
  EXPECT_TRUE(report.valid) << Describe(report);
}

TEST(SubmapSearch, ReachesPlainArrayWithOtherParameters) {
  SubmapSearchOptions options;
  options.rows = 9;
  options.cols = 40;
  options.constraints.window = 5;
  options.constraints.min_weight = 3;
  options.constraints.min_hamming = 2;
  options.constraints.torus = false;
  const SubmapSearchResult result = SearchPerfectSubmap(options);
  ASSERT_TRUE(result.reached) << result.termination;
  EXPECT_TRUE(VerifyPattern(result.array, options.constraints).valid);
}

TEST(SubmapSearch, DeterministicForASeed) {
  SubmapSearchOptions options;
  options.rows = 6;
  options.cols = 80;
  options.seed = 5;
  const auto a = SearchPerfectSubmap(options);
  const auto b = SearchPerfectSubmap(options);
  EXPECT_EQ(a.array, b.array);
  EXPECT_EQ(a.moves, b.moves);
  options.seed = 6;
  EXPECT_FALSE(SearchPerfectSubmap(options).array == a.array);
}

TEST(SubmapSearch, ReportsHonestlyWhenASizeIsNotReached) {
  // A 3 x 8 torus of 3 x 3 windows with 2 isolated spots or more needs 24 of the 25 such
  // windows: 2000 moves do not reach it (a distance no two windows can have is refused before
  // the search, RefusesArraysNoPatternCanFill). The search must say so and return its best.
  SubmapSearchOptions options;
  options.rows = 3;
  options.cols = 8;
  options.constraints.window = 3;
  options.constraints.min_weight = 2;
  options.max_moves = 2000;
  const auto result = SearchPerfectSubmap(options);
  EXPECT_FALSE(result.reached);
  EXPECT_EQ(result.termination, "move budget");
  EXPECT_GT(result.final_cost, 0);
  EXPECT_FALSE(VerifyPattern(result.array, options.constraints).valid);
}

TEST(SubmapSearch, ProgressCallbackCanStop) {
  SubmapSearchOptions options;
  options.rows = 3;
  options.cols = 8;
  options.constraints.window = 3;
  options.constraints.min_weight = 2;
  options.progress_interval_moves = 10;
  int calls = 0;
  options.progress = [&](const SubmapSearchProgress& p) {
    EXPECT_GT(p.moves, 0);
    return ++calls < 3;
  };
  const auto result = SearchPerfectSubmap(options);
  EXPECT_EQ(result.termination, "stopped");
  EXPECT_EQ(calls, 3);
}

TEST(SubmapSearch, ShippedArrayIsReproducibleFromItsSeed) {
  const auto result = SearchPerfectSubmap(DefaultPatternSearchOptions());
  ASSERT_TRUE(result.reached);
  EXPECT_EQ(result.array, DefaultPatternArray());
}

TEST(SubmapSearch, RejectsBadOptions) {
  SubmapSearchOptions options;
  options.rows = 4;  // smaller than the window
  EXPECT_THROW(SearchPerfectSubmap(options), std::invalid_argument);
  options = {};
  options.constraints.window = 9;
  EXPECT_THROW(SearchPerfectSubmap(options), std::invalid_argument);
}

// The refusal's text, or "" when the options pass.
std::string Refusal(const SubmapSearchOptions& options) {
  try {
    options.Check();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(SubmapSearch, RefusesArraysNoPatternCanFill) {
  // 3x3 windows of isolated spots with at least 2 spots: 25 exist (counted by hand, brute
  // force over all 512 windows), so a 3x8 torus (24 windows) may exist and a 3x9 (27) cannot.
  SubmapSearchOptions options;
  options.constraints.window = 3;
  options.constraints.min_weight = 2;
  options.rows = 3;
  options.cols = 8;
  EXPECT_EQ(Refusal(options), "");
  options.cols = 9;
  EXPECT_NE(Refusal(options).find("only 25 distinct 3x3 windows"), std::string::npos)
      << Refusal(options);
  // A 2x2 window holds one isolated spot at most, so two windows differ in 2 spots at most.
  options = {};
  options.constraints.window = 2;
  options.constraints.min_weight = 0;
  options.constraints.min_hamming = 3;
  options.rows = options.cols = 2;
  EXPECT_NE(Refusal(options).find("at most 1 2x2 windows"), std::string::npos) << Refusal(options);
  // One window has no pair to differ from.
  options = {};
  options.constraints.torus = false;
  options.rows = options.cols = 6;
  EXPECT_NE(Refusal(options).find("holds one 6x6 window"), std::string::npos) << Refusal(options);
}

}  // namespace
}  // namespace sewer3d
