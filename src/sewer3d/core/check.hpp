#pragma once
/// \file
/// Precondition checks. A broken precondition is a programming error or misuse of an API:
/// it throws std::invalid_argument naming the condition, so callers (and `main`) can report it.

#include <sstream>
#include <stdexcept>
#include <string>

namespace sewer3d::internal {

[[noreturn]] inline void ThrowCheckFailure(const char* condition, const char* file, int line,
                                           const std::string& message) {
  std::ostringstream out;
  out << "check failed: " << condition;
  if (!message.empty()) out << " (" << message << ")";
  out << " at " << file << ":" << line;
  throw std::invalid_argument(out.str());
}

}  // namespace sewer3d::internal

/// Throws std::invalid_argument when `condition` is false. The optional message is
/// streamed: SEWER3D_CHECK(n > 0, "n = " << n).
#define SEWER3D_CHECK(condition, ...)                                        \
  do {                                                                       \
    if (!(condition)) {                                                      \
      std::ostringstream sewer3d_check_message_;                             \
      sewer3d_check_message_ << "" __VA_OPT__(<<) __VA_ARGS__;               \
      ::sewer3d::internal::ThrowCheckFailure(#condition, __FILE__, __LINE__, \
                                             sewer3d_check_message_.str());  \
    }                                                                        \
  } while (false)
