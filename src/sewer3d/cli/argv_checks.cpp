#include "sewer3d/cli/argv_checks.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cctype>
#include <vector>

#include "sewer3d/core/edit_distance.hpp"

namespace sewer3d::cli {
namespace {

// The long option `--name` of `app` or one of its (sub)commands; nullptr when none has it.
const CLI::Option* FindLongOption(const CLI::App& app, const std::string& name) {
  if (const CLI::Option* o = app.get_option_no_throw("--" + name)) return o;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
    if (const CLI::Option* o = FindLongOption(*sub, name)) return o;
  }
  return nullptr;
}

// Every long option name (without the dashes) of `app` and its (sub)commands.
void LongOptionNames(const CLI::App& app, std::vector<std::string>& names) {
  for (const CLI::Option* o : app.get_options()) {
    for (const std::string& name : o->get_lnames()) names.push_back(name);
  }
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
    LongOptionNames(*sub, names);
}

// "name" of "--name" or "--name=value"; empty for anything else.
std::string LongName(const std::string& arg) {
  return arg.size() > 2 && arg.rfind("--", 0) == 0 ? arg.substr(2, arg.find('=') - 2)
                                                   : std::string();
}

}  // namespace

std::string SingleDashLongOption(const CLI::App& app, int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    std::string arg = argv[i];
    if (arg == "--") break;
    if (arg.size() < 3 || arg[0] != '-' || std::isalpha(static_cast<unsigned char>(arg[1])) == 0) {
      continue;
    }
    if (FindLongOption(app, arg.substr(1, arg.find('=') - 1)) != nullptr) return arg;
  }
  return {};
}

std::string UnknownLongOption(const CLI::App& app, int argc, char** argv) {
  std::vector<std::string> names;
  LongOptionNames(app, names);
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--") break;
    const std::string name = LongName(arg);
    if (name.empty() || std::find(names.begin(), names.end(), name) != names.end()) continue;
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
  for (int i = 1; i + 1 < argc; ++i) {
    const std::string arg = argv[i], next = argv[i + 1];
    if (arg == "--") break;
    if (arg.find('=') != std::string::npos) continue;
    const CLI::Option* option = FindLongOption(app, LongName(arg));
    if (option == nullptr || option->get_items_expected_min() == 0) continue;  // a flag
    const std::string name = LongName(next);
    if (!name.empty() && FindLongOption(app, name) != nullptr) {
      return fmt::format(
          "{0}: takes a value, but the next argument is the option {1} (give {0} its value first)",
          arg, next);
    }
  }
  return {};
}

}  // namespace sewer3d::cli
