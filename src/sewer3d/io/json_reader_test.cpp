#include "sewer3d/io/json_reader.hpp"

#include <gtest/gtest.h>

#include <string>

namespace sewer3d {
namespace {

// The account JsonReader gives of `text`'s syntax error.
std::string ProblemOf(const std::string& text) {
  try {
    (void)nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    return JsonSyntaxProblem(text, e.byte, e.what());
  }
  return "parsed";
}

TEST(JsonSyntaxProblem, GivesLineColumnAndWhatWasWanted) {
  const std::string comma = ProblemOf("{\n  \"fx\": 433.4,\n  \"fy\": 433.4,\n}\n");
  EXPECT_EQ(comma.rfind("invalid JSON at line 4, column 1 ('}' after \"", 0), 0u) << comma;
  EXPECT_NE(comma.find("\"fy\": 433.4, \""), std::string::npos) << comma;
  EXPECT_NE(comma.find("a comma too many"), std::string::npos) << comma;
  const std::string quotes = ProblemOf("{'fx': 1}");
  EXPECT_NE(quotes.find("line 1, column 2 (''' after \"{\")"), std::string::npos) << quotes;
  const std::string cut = ProblemOf("{\"camera\": {\"width\": 2592,");
  EXPECT_NE(cut.find("(the end after"), std::string::npos) << cut;
  EXPECT_NE(cut.find("cut short?"), std::string::npos) << cut;
  const std::string bare = ProblemOf("{\"a\": yes}");
  EXPECT_NE(bare.find("no comments, single quotes or bare words"), std::string::npos) << bare;
  const std::string line = ProblemOf("{\"a\": \"one\ntwo\"}");
  EXPECT_NE(line.find("raw line break"), std::string::npos) << line;
}

TEST(JsonSyntaxProblem, NamesAFileThatIsNotJsonAtAll) {
  EXPECT_EQ(ProblemOf("time_s,distance_mm\n0,0\n"),
            "is not JSON (it begins with \"time_s,distance_mm\"; a JSON file begins with '{')");
  EXPECT_EQ(ProblemOf("// my module\n{}"),
            "is not JSON (it begins with \"// my module\"; a JSON file begins with '{')");
  // A byte-order mark before the '{' is JSON still: the error is the one inside.
  EXPECT_NE(ProblemOf("\xEF\xBB\xBF{\"a\": }").find("line 1, column"), std::string::npos);
}

}  // namespace
}  // namespace sewer3d
