#include "sewer3d/cli/exit_code.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <filesystem>
#include <new>
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

}  // namespace sewer3d::cli
