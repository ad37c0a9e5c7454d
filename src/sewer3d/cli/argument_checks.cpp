#include "sewer3d/cli/argument_checks.hpp"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <nlohmann/json.hpp>

#include "sewer3d/core/check.hpp"
#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/text_file.hpp"
#include "sewer3d/pipeline/workspace.hpp"

namespace sewer3d::cli {
namespace {

// Whether `value` reads as a floating-point NaN ("nan", "-NaN", "nan(1)"): ranges never refuse
// it (every comparison with NaN is false).
bool IsNan(const std::string& value) {
  char* end = nullptr;
  const double x = std::strtod(value.c_str(), &end);
  return !value.empty() && end == value.c_str() + value.size() && std::isnan(x);
}

// Whether some (sub)command of `app` has the long option `--name`.
bool HasLongOption(const CLI::App& app, const std::string& name) {
  if (app.get_option_no_throw("--" + name) != nullptr) return true;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
    if (HasLongOption(*sub, name)) return true;
  }
  return false;
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

CLI::Validator FileNameEnding(const std::string& extension, const std::string& why) {
  return {[extension, why](std::string& name) {
            const std::filesystem::path path(name);
            if (path.extension() == extension && !path.stem().empty()) return std::string();
            return why + ": a file name ending in " + extension +
                   (path.filename() == extension ? " with a name before it" : "") + ", got " + name;
          },
          extension.substr(1)};
}

void CheckNotInRunOrWorkspace(const std::filesystem::path& folder, const char* flag) {
  const auto owner = OwnerAbove(folder, {"run.json", "workspace.json"}, true);
  if (owner.empty()) return;
  if (owner.filename() == "run.json") {
    throw InvalidValue(flag, folder.string() + " lies in the capture run " +
                                 owner.parent_path().string() +
                                 ": outputs there would mix with the run as captured; choose "
                                 "another folder");
  }
  throw InvalidValue(flag, folder.string() + " lies in the processing workspace " +
                               owner.parent_path().string() +
                               ": outputs there would replace or mix with its stages' files; "
                               "choose another folder");
}

void CheckFileNotInRunOrWorkspace(const std::filesystem::path& file, const char* flag) {
  const std::filesystem::path folder = file.parent_path();
  CheckNotInRunOrWorkspace(folder.empty() ? std::filesystem::path(".") : folder, flag);
}

void CheckNotAModulesMatrix(const std::filesystem::path& out) {
  if (out.filename() != "pattern.png") return;
  const std::filesystem::path folder = out.has_parent_path() ? out.parent_path() : ".";
  for (const char* owner : {"module.json", "rig.json"}) {
    if (IsRegularFile(folder / owner)) {
      throw InvalidValue("--out", out.string() + " is the pattern matrix of the " +
                                      (folder / owner).string() +
                                      " beside it; write the new pattern elsewhere");
    }
  }
}

void CheckNotAModuleFile(const std::filesystem::path& out, const char* flag,
                         const std::string& writes) {
  constexpr std::uintmax_t kMaxModuleBytes = 1 << 20;  // a module file is a few kB
  if (!IsRegularFile(out)) return;
  bool module = out.filename() == "module.json";
  std::error_code ec;
  if (!module && std::filesystem::file_size(out, ec) < kMaxModuleBytes && !ec) {
    const nlohmann::json j = nlohmann::json::parse(ReadTextFile(out), nullptr, false);
    module = j.is_object() && j.contains("projector");
  }
  if (!module) return;
  throw InvalidValue(flag, out.string() + " is a module description; this command writes " +
                               writes + ", which would replace it: write it elsewhere");
}

void CheckWorkspaceExists(const std::filesystem::path& folder, const std::string& stage) {
  if (std::filesystem::is_directory(folder)) return;
  throw FileError(folder, "workspace folder not found: `sewer3d " + stage +
                              "` continues the workspace of `sewer3d rgbd` (or of `sewer3d "
                              "process`); is --out mistyped?");
}

}  // namespace sewer3d::cli
