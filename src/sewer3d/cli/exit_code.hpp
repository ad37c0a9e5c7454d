#pragma once
/// \file
/// How an error that ends a `sewer3d` command becomes an exit status and a one-line message
/// (the README's exit-code table).

#include <exception>
#include <string>

namespace sewer3d::cli {

/// Exit statuses of the `sewer3d` binary.
enum ExitCode : int {
  kExitOk = 0,
  kExitTaskFailed = 1,   ///< the command ran but could not do its task (e.g. no pattern found)
  kExitUsage = 2,        ///< bad command line, or an option value the library rejected
  kExitBadFile = 3,      ///< an input file is missing, unreadable, malformed or inconsistent
  kExitInternal = 4,     ///< a bug: a broken internal invariant or an unexpected exception
  kExitOutOfMemory = 5,  ///< memory ran out
};

struct ErrorExit {
  int code = kExitInternal;
  std::string message;  ///< one line, to follow "sewer3d: error: "
};

/// Classifies the exception that ended a command: CLI parse errors and InvalidValue /
/// std::invalid_argument (an option value a library rejected) → kExitUsage; FileError and
/// std::filesystem::filesystem_error → kExitBadFile; std::bad_alloc → kExitOutOfMemory;
/// InternalError, any other exception and non-std exceptions → kExitInternal with "internal
/// error, please report: …". Line breaks in messages become spaces.
ErrorExit ExitForError(const std::exception_ptr& error);

/// CLI11's range refusal ("--rows: Value 12.5 not in range 2 to 4096") in the words of the other
/// value errors: "--rows: expected a whole number from 2 to 4096, got 12.5" (`whole`: the option
/// takes integers; otherwise "a number"). CLI11's "Could not convert: --rows = 1.5" becomes
/// "--rows: expected a whole number, got 1.5". Counts too: "--module: At Most 1 required but
/// received 2" becomes "--module: given 2 times; give it once", "--axis: At least 3 required but
/// received 2" "--axis: takes 3 values, got 2". Any other message comes back unchanged.
std::string ReadableParseError(const std::string& message, bool whole);

/// The exit code of a CLI11 refusal: kExitBadFile for a file option naming a missing file or a
/// folder (as a loader's refusal of the same file), kExitUsage for the rest.
int ParseErrorExit(const std::string& message);

}  // namespace sewer3d::cli
