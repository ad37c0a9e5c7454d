#pragma once
/// \file
/// The two kinds of checks (the README's exit-code table says what the CLI makes of them):
///
/// - **Validation** of values a caller supplies (every `Options::Check()`, scenes, scenarios,
///   pipe worlds, rigs, modules): SEWER3D_VALIDATE throws InvalidValue, a
///   std::invalid_argument whose message is "FIELD: PROBLEM" in the user's terms — the field
///   as the scene, scenario or module file (or the CLI option) names it, the value, and what
///   is allowed — without a source location. io/ turns it into a FileError naming the file;
///   when it reaches `main` it is a usage error.
/// - **Internal invariants** that no input can break: SEWER3D_CHECK throws InternalError, a
///   std::logic_error that is deliberately not an std::invalid_argument, naming the condition
///   and file:line; `main` reports it as "internal error, please report".

#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

namespace sewer3d {

/// A caller-supplied value that is not allowed. what() is "FIELD: PROBLEM" (just PROBLEM when
/// no single field is to blame).
class InvalidValue : public std::invalid_argument {
 public:
  InvalidValue(const std::string& field, const std::string& problem)
      : std::invalid_argument(field.empty() ? problem : field + ": " + problem),
        field_(field),
        problem_(problem) {}
  /// The field as the user wrote it, e.g. "motion.speed_mm_s" or "features[2].radius_mm".
  const std::string& field() const { return field_; }
  /// What is wrong: the value and what is allowed, e.g. "must be > 0, got -5".
  const std::string& problem() const { return problem_; }

 private:
  std::string field_, problem_;
};

/// A broken internal invariant: a bug in sewer3d whatever the input.
class InternalError : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

/// Runs `check()` and puts `prefix` in front of the field of an InvalidValue it throws, so that
/// a containing object's Check() names its members as its file does: "motion." + "speed_mm_s".
template <typename CheckFn>
void CheckWithin(const std::string& prefix, CheckFn&& check) {
  try {
    std::forward<CheckFn>(check)();
  } catch (const InvalidValue& e) {
    // A problem of the whole member ("pipe.") is named by the member ("pipe").
    const bool whole = e.field().empty() && !prefix.empty() && prefix.back() == '.';
    throw InvalidValue(whole ? prefix.substr(0, prefix.size() - 1) : prefix + e.field(),
                       e.problem());
  }
}

namespace internal {

[[noreturn]] inline void ThrowInternalError(const char* condition, const char* file, int line,
                                            const std::string& message) {
  std::ostringstream out;
  out << "check failed: " << condition;
  if (!message.empty()) out << " (" << message << ")";
  out << " at " << file << ":" << line;
  throw InternalError(out.str());
}

}  // namespace internal
}  // namespace sewer3d

/// Internal invariant: throws sewer3d::InternalError naming the condition and file:line when
/// `condition` is false. The optional message is streamed: SEWER3D_CHECK(n > 0, "n = " << n).
#define SEWER3D_CHECK(condition, ...)                                         \
  do {                                                                        \
    if (!(condition)) {                                                       \
      std::ostringstream sewer3d_check_message_;                              \
      sewer3d_check_message_ << "" __VA_OPT__(<<) __VA_ARGS__;                \
      ::sewer3d::internal::ThrowInternalError(#condition, __FILE__, __LINE__, \
                                              sewer3d_check_message_.str());  \
    }                                                                         \
  } while (false)

/// Validation of a caller-supplied value: throws sewer3d::InvalidValue(field, problem) when
/// `condition` is false. `field` is a string expression naming the field as the user's file or
/// option does; the problem is streamed and says the value and what is allowed:
/// SEWER3D_VALIDATE(speed_mm_s > 0.0, "speed_mm_s", "must be > 0, got " << speed_mm_s).
#define SEWER3D_VALIDATE(condition, field, ...)                              \
  do {                                                                       \
    if (!(condition)) {                                                      \
      std::ostringstream sewer3d_validate_problem_;                          \
      sewer3d_validate_problem_ << "" __VA_OPT__(<<) __VA_ARGS__;            \
      throw ::sewer3d::InvalidValue(field, sewer3d_validate_problem_.str()); \
    }                                                                        \
  } while (false)

namespace sewer3d {

/// Validation shorthand: InvalidValue(field, "must be > 0, got V") unless value > 0.
inline void ValidatePositive(const std::string& field, double value) {
  SEWER3D_VALIDATE(value > 0.0, field, "must be > 0, got " << value);
}

/// Validation shorthand: InvalidValue(field, "must not be negative, got V") unless value >= 0.
inline void ValidateNotNegative(const std::string& field, double value) {
  SEWER3D_VALIDATE(value >= 0.0, field, "must not be negative, got " << value);
}

/// Validation shorthand: a clock position in hours seen along the flow, 0..12 (0 and 12 are
/// both the crown); NaN and anything else are refused.
inline void ValidateClockHours(const std::string& field, double hours) {
  SEWER3D_VALIDATE(hours >= 0.0 && hours <= 12.0, field,
                   "a clock position must be 0..12 h, got " << hours);
}

}  // namespace sewer3d
