#include "sewer3d/cli/exit_code.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <filesystem>
#include <new>
#include <regex>
#include <stdexcept>

#include "sewer3d/io/file_error.hpp"

namespace sewer3d::cli {
namespace {

ErrorExit Exit(int code, std::string message) {
  // One line on stderr whatever the message (OpenCV's, for one, spans several).
  std::replace(message.begin(), message.end(), '\n', ' ');
  std::replace(message.begin(), message.end(), '\r', ' ');
  while (!message.empty() && message.back() == ' ') message.pop_back();
  return {code, std::move(message)};
}

// A bound as CLI11 prints it ("10.000000") without the trailing zeros ("10").
std::string Bound(std::string text) {
  if (text.find('.') == std::string::npos) return text;
  while (text.back() == '0') text.pop_back();
  if (text.back() == '.') text.pop_back();
  return text;
}

}  // namespace

ErrorExit ExitForError(const std::exception_ptr& error) {
  // Order matters: FileError and CLI::ParseError are runtime_errors, InternalError and
  // invalid_argument are logic_errors; the specific kinds come before their bases.
  try {
    std::rethrow_exception(error);
  } catch (const FileError& e) {
    return Exit(kExitBadFile, e.what());
  } catch (const std::filesystem::filesystem_error& e) {
    return Exit(kExitBadFile, e.what());
  } catch (const CLI::ParseError& e) {
    return Exit(kExitUsage, std::string(e.what()) + " (see sewer3d --help)");
  } catch (const std::invalid_argument& e) {
    return Exit(kExitUsage, std::string("invalid value: ") + e.what());
  } catch (const std::bad_alloc&) {
    return Exit(kExitOutOfMemory, "out of memory");
  } catch (const std::exception& e) {
    // InternalError (a broken invariant), and whatever else no code path expects.
    return Exit(kExitInternal, std::string("internal error, please report: ") + e.what());
  } catch (...) {
    return Exit(kExitInternal, "internal error, please report: unknown exception");
  }
}

int ParseErrorExit(const std::string& message) {
  static const std::regex file("^\\S+: File (does not exist|is actually a directory): .+$");
  return std::regex_match(message, file) ? kExitBadFile : kExitUsage;
}

std::string ReadableParseError(const std::string& message, bool whole) {
  static const std::regex range("^(.*): Value (.*) not in range (\\S+) to (\\S+)$");
  static const std::regex convert("^Could not convert: (\\S+) = (.*)$");
  static const std::regex empty_file("^(\\S+): File does not exist: $");
  static const std::regex at_most("^(\\S+): At Most (\\d+) required but received (\\d+)$");
  static const std::regex at_least("^(\\S+): At least (\\d+) required but received (\\d+)$");
  static const std::regex member("^(\\S+): (.*) not in \\{(.*)\\}$");
  std::smatch m;
  if (std::regex_match(message, m, empty_file)) return m[1].str() + ": must not be empty";
  static const std::regex folder("^(\\S+): File is actually a directory: (.+)$");
  static const std::regex no_file("^(\\S+): File does not exist: (.+)$");
  if (std::regex_match(message, m, folder))
    return m[1].str() + ": " + m[2].str() + " is a folder, not a file";
  if (std::regex_match(message, m, no_file))
    return m[1].str() + ": " + m[2].str() + ": no such file";
  if (std::regex_match(message, m, member)) {
    const std::string choices = std::regex_replace(m[3].str(), std::regex(","), ", ");
    if (m[2].str().empty()) return m[1].str() + ": must not be empty (one of " + choices + ")";
    return m[1].str() + ": expected one of " + choices + ", got " + m[2].str();
  }
  if (std::regex_match(message, m, at_most)) {
    if (m[2].str() == "1") return m[1].str() + ": given " + m[3].str() + " times; give it once";
    return m[1].str() + ": takes at most " + m[2].str() + " values, got " + m[3].str();
  }
  if (std::regex_match(message, m, at_least)) {
    return m[1].str() + ": takes " + m[2].str() + " values, got " + m[3].str();
  }
  if (std::regex_match(message, m, convert)) {
    return m[1].str() + ": expected " + (whole ? "a whole number" : "a number") + ", got " +
           m[2].str();
  }
  if (!std::regex_match(message, m, range)) return message;
  return m[1].str() + ": expected " + (whole ? "a whole number" : "a number") + " from " +
         Bound(m[3].str()) + " to " + Bound(m[4].str()) + ", got " + m[2].str();
}

}  // namespace sewer3d::cli
