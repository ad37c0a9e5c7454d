#include "sewer3d/cli/exit_code.hpp"

#include <gtest/gtest.h>

#include <CLI/CLI.hpp>
#include <filesystem>
#include <new>
#include <stdexcept>
#include <string>
#include <system_error>

#include "sewer3d/core/check.hpp"
#include "sewer3d/io/file_error.hpp"

namespace sewer3d::cli {
namespace {

template <typename E>
ErrorExit ExitFor(const E& error) {
  return ExitForError(std::make_exception_ptr(error));
}

TEST(ExitCode, BadFileNamesTheFile) {
  const ErrorExit e =
      ExitFor(FileError("run/scenario.json", "pipe.joints: 2 sections need 1 joint"));
  EXPECT_EQ(e.code, kExitBadFile);
  EXPECT_EQ(e.message, "run/scenario.json: pipe.joints: 2 sections need 1 joint");
  const std::filesystem::filesystem_error fs_error(
      "cannot create directories", "out/x", std::make_error_code(std::errc::permission_denied));
  EXPECT_EQ(ExitFor(fs_error).code, kExitBadFile);
}

TEST(ExitCode, RangeRefusalsSayWhatIsExpected) {
  // A missing input file or a folder is a bad file (3), as the loaders say; the rest usage (2).
  EXPECT_EQ(ParseErrorExit("--module: File does not exist: nope/module.json"), kExitBadFile);
  EXPECT_EQ(ParseErrorExit("--images: File is actually a directory: calib"), kExitBadFile);
  EXPECT_EQ(ParseErrorExit("--module: File does not exist: "), kExitUsage);  // empty value
  EXPECT_EQ(ParseErrorExit("--rows: Value 12.5 not in range 2 to 4096"), kExitUsage);
  EXPECT_EQ(ReadableParseError("--rows: Value 12.5 not in range 2 to 4096", true),
            "--rows: expected a whole number from 2 to 4096, got 12.5");
  EXPECT_EQ(ReadableParseError("--tilt-deg: Value 9x not in range -80 to 80", false),
            "--tilt-deg: expected a number from -80 to 80, got 9x");
  EXPECT_EQ(ReadableParseError("--d: Value 9 not in range 10.000000 to 0.050000", false),
            "--d: expected a number from 10 to 0.05, got 9");
  EXPECT_EQ(ReadableParseError("Could not convert: --seed = 1.5", true),
            "--seed: expected a whole number, got 1.5");
  EXPECT_EQ(ReadableParseError("--images: File does not exist: ", false),
            "--images: must not be empty");
  EXPECT_EQ(ReadableParseError("--out is required", true), "--out is required");
  EXPECT_EQ(ReadableParseError("--images: File is actually a directory: cal/pose_00", false),
            "--images: cal/pose_00 is a folder, not a file");
  EXPECT_EQ(ReadableParseError("--module: File does not exist: m.json", false),
            "--module: m.json: no such file");
  EXPECT_EQ(ReadableParseError("--edges:  not in {feature,rig,none}", false),
            "--edges: must not be empty (one of feature, rig, none)");
  EXPECT_EQ(ReadableParseError("--init: fast not in {odometry,chordal}", false),
            "--init: expected one of odometry, chordal, got fast");
  EXPECT_EQ(ReadableParseError("--module: At Most 1 required but received 2", false),
            "--module: given 2 times; give it once");
  EXPECT_EQ(ReadableParseError("--axis: At least 3 required but received 2", false),
            "--axis: takes 3 values, got 2");
  EXPECT_EQ(ReadableParseError("--size: At Most 2 required but received 3", false),
            "--size: takes at most 2 values, got 3");
}

TEST(ExitCode, RejectedValuesAreUsageErrors) {
  const ErrorExit e = ExitFor(InvalidValue("supersampling", "must be 1..16, got 0"));
  EXPECT_EQ(e.code, kExitUsage);
  EXPECT_EQ(e.message, "invalid value: supersampling: must be 1..16, got 0");
  EXPECT_EQ(ExitFor(std::invalid_argument("bad")).code, kExitUsage);
  const ErrorExit parse = ExitFor(CLI::RequiredError("--out"));
  EXPECT_EQ(parse.code, kExitUsage);
  EXPECT_NE(parse.message.find("--out"), std::string::npos);
}

TEST(ExitCode, InternalErrorsAskForAReport) {
  try {
    SEWER3D_CHECK(1 + 1 == 3, "arithmetic");
  } catch (...) {
    const ErrorExit e = ExitForError(std::current_exception());
    EXPECT_EQ(e.code, kExitInternal);
    EXPECT_EQ(e.message.rfind("internal error, please report: check failed: 1 + 1 == 3", 0), 0u)
        << e.message;
    EXPECT_NE(e.message.find("exit_code_test.cpp:"), std::string::npos) << e.message;
  }
  // Exceptions no code path expects are bugs too.
  EXPECT_EQ(ExitFor(std::out_of_range("vector")).code, kExitInternal);
  EXPECT_EQ(ExitFor(std::runtime_error("?")).code, kExitInternal);
  EXPECT_EQ(ExitFor(42).code, kExitInternal);
  EXPECT_NE(kExitInternal, kExitUsage);
  EXPECT_NE(kExitInternal, kExitBadFile);
  EXPECT_NE(kExitInternal, kExitTaskFailed);
}

TEST(ExitCode, OutOfMemory) {
  const ErrorExit e = ExitFor(std::bad_alloc());
  EXPECT_EQ(e.code, kExitOutOfMemory);
  EXPECT_EQ(e.message, "out of memory");
}

TEST(ExitCode, AFileNameWithANewlineIsShownEscaped) {
  const ErrorExit e = ExitFor(FileError("runs/a\nb\x01.png", "cannot be read"));
  EXPECT_EQ(e.message, "runs/a\\nb\\x01.png: cannot be read");
}

TEST(ExitCode, MessagesAreOneLine) {
  const ErrorExit e = ExitFor(std::runtime_error("OpenCV(4.6) error:\nsomething\n"));
  EXPECT_EQ(e.message.find('\n'), std::string::npos) << e.message;
  EXPECT_NE(e.message.find("error: something"), std::string::npos) << e.message;
}

}  // namespace
}  // namespace sewer3d::cli
