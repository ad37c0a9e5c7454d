#include "sewer3d/cli/argument_checks.hpp"

#include <fmt/core.h>

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "sewer3d/core/check.hpp"
#include "sewer3d/core/edit_distance.hpp"

namespace sewer3d::cli {
namespace {

// Whether `value` reads as a floating-point NaN ("nan", "-NaN", "nan(1)"): ranges never refuse
// it (every comparison with NaN is false).
bool IsNan(const std::string& value) {
  char* end = nullptr;
  const double x = std::strtod(value.c_str(), &end);
  return !value.empty() && end == value.c_str() + value.size() && std::isnan(x);
}

// The long option `--name` of `app` or one of its (sub)commands; nullptr when none has it.
const CLI::Option* FindLongOption(const CLI::App& app, const std::string& name) {
  if (const CLI::Option* o = app.get_option_no_throw("--" + name)) return o;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
    if (const CLI::Option* o = FindLongOption(*sub, name)) return o;
  }
  return nullptr;
}

bool HasLongOption(const CLI::App& app, const std::string& name) {
  return FindLongOption(app, name) != nullptr;
}

}  // namespace

// The first option or argument of the chosen subcommands given as an empty string ("" names
// no file and no value) or as NaN, with what is wrong; nullptr when none.
std::pair<const CLI::Option*, const char*> BadValue(const CLI::App& app) {
  for (const CLI::Option* option : app.get_options()) {
    if (option->count() == 0) continue;
    for (const std::string& value : option->results()) {
      if (value.empty()) return {option, "must not be empty"};
      if (IsNan(value)) return {option, "must be a number, got NaN"};
    }
  }
  for (const CLI::App* sub : app.get_subcommands()) {
    if (const auto bad = BadValue(*sub); bad.first != nullptr) return bad;
  }
  return {nullptr, nullptr};
}

// Whether the option that a CLI11 message starts with ("--rows: …") takes whole numbers, looked
// up in the chosen subcommands.
bool TakesWholeNumbers(const CLI::App& app, const std::string& message) {
  static const std::string convert = "Could not convert: ";
  const std::string name =
      message.rfind(convert, 0) == 0
          ? message.substr(convert.size(), message.find(' ', convert.size()) - convert.size())
          : message.substr(0, message.find(':'));
  for (const CLI::App* sub : app.get_subcommands()) {
    if (const CLI::Option* option = sub->get_option_no_throw(name); option != nullptr) {
      const std::string type = option->get_type_name();
      return type.rfind("INT", 0) == 0 || type.rfind("UINT", 0) == 0;
    }
    if (TakesWholeNumbers(*sub, message)) return true;
  }
  return false;
}

// What a missing argument or subcommand of the deepest chosen subcommand is for, in place of
// CLI11's "KIND is required" or "A subcommand is required"; empty for any other message.
std::string MissingArgument(const CLI::App& app, const std::string& message) {
  const CLI::App* deepest = &app;
  while (!deepest->get_subcommands().empty()) deepest = deepest->get_subcommands().front();
  const std::string command = deepest == &app ? "sewer3d" : deepest->get_name();
  if (message == "A subcommand is required") {
    std::string names;
    for (const CLI::App* sub : deepest->get_subcommands([](const CLI::App*) { return true; })) {
      names += (names.empty() ? "" : ", ") + sub->get_name();
    }
    return command + " needs a subcommand: " + names;
  }
  static const std::string required = " is required";
  if (message.size() <= required.size() ||
      message.compare(message.size() - required.size(), required.size(), required) != 0) {
    return {};
  }
  const CLI::Option* option =
      deepest->get_option_no_throw(message.substr(0, message.size() - required.size()));
  if (option == nullptr || !option->get_positional()) return {};
  return command + " needs its " + option->get_name() + " argument: " + option->get_description();
}

// The first argument written as a long option with one dash ("-out"), which CLI11 would read as
// the short flags -o -u -t and then report --out as missing; empty when none.
std::string SingleDashLongOption(const CLI::App& app, int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    std::string arg = argv[i];
    if (arg == "--") break;
    if (arg.size() < 3 || arg[0] != '-' || std::isalpha(static_cast<unsigned char>(arg[1])) == 0) {
      continue;
    }
    if (HasLongOption(app, arg.substr(1, arg.find('=') - 1))) return arg;
  }
  return {};
}

namespace {

// Every long option name (without the dashes) of `app` and its (sub)commands.
void LongOptionNames(const CLI::App& app, std::vector<std::string>& names) {
  for (const CLI::Option* o : app.get_options()) {
    for (const std::string& name : o->get_lnames()) names.push_back(name);
  }
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
    LongOptionNames(*sub, names);
}

}  // namespace

std::string UnknownLongOption(const CLI::App& app, int argc, char** argv) {
  std::vector<std::string> names;
  LongOptionNames(app, names);
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--") break;
    if (arg.size() < 3 || arg.rfind("--", 0) != 0) continue;
    const std::string name = arg.substr(2, arg.find('=') - 2);
    if (HasLongOption(app, name)) continue;
    std::string nearest;
    std::size_t best = 3;  // at most two edits away
    for (const std::string& known : names) {
      if (const std::size_t d = EditDistance(name, known); d < best) best = d, nearest = known;
    }
    return "unknown option --" + name +
           (nearest.empty() ? "" : " (did you mean --" + nearest + "?)");
  }
  return {};
}

std::string FlagGivenAsValue(const CLI::App& app, int argc, char** argv) {
  const auto long_name = [](const std::string& arg) {
    return arg.size() > 2 && arg.rfind("--", 0) == 0 ? arg.substr(2, arg.find('=') - 2)
                                                     : std::string();
  };
  for (int i = 1; i + 1 < argc; ++i) {
    const std::string arg = argv[i], next = argv[i + 1];
    if (arg == "--") break;
    if (arg.find('=') != std::string::npos) continue;
    const CLI::Option* option = FindLongOption(app, long_name(arg));
    if (option == nullptr || option->get_items_expected_min() == 0) continue;  // a flag
    const std::string name = long_name(next);
    if (!name.empty() && HasLongOption(app, name)) {
      return fmt::format(
          "{0}: takes a value, but the next argument is the option {1} (give {0} its value first)",
          arg, next);
    }
  }
  return {};
}

CLI::Validator FileNameEnding(const std::string& extension, const std::string& why) {
  return {[extension, why](std::string& name) {
            const std::filesystem::path path(name);
            if (path.extension() == extension && !path.stem().empty()) return std::string();
            return why + ": a file name ending in " + extension +
                   (path.filename() == extension ? " with a name before it" : "") + ", got " + name;
          },
          extension.substr(1)};
}

}  // namespace sewer3d::cli
