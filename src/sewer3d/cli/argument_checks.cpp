#include "sewer3d/cli/argument_checks.hpp"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <string>

#include "sewer3d/core/check.hpp"
#include "sewer3d/triangulate/reconstruct_frame.hpp"

namespace sewer3d::cli {
namespace {

// Whether `value` reads as a floating-point NaN ("nan", "-NaN", "nan(1)"): ranges never refuse
// it (every comparison with NaN is false).
bool IsNan(const std::string& value) {
  char* end = nullptr;
  const double x = std::strtod(value.c_str(), &end);
  return !value.empty() && end == value.c_str() + value.size() && std::isnan(x);
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

void SpotFlags::ApplyTo(FrameReconstructionOptions& options) const {
  options.decoder.niblack.min_contrast_3x3 = faint_spots;
  options.lost_spots.enabled = !no_lost_spots;
  options.cut_spots.enabled = !no_cut_spots;
}

void AddSpotFlags(CLI::App* command, SpotFlags* flags) {
  command
      ->add_option("--faint-spots", flags->faint_spots,
                   "Also find spots whose 3x3 mean is LEVELS grey levels (8-bit) over the local "
                   "mean where the background is quiet: black walls (polyethylene), dark "
                   "deposits; 2 finds nine tenths of a black wall's spots, about 10 ms more per "
                   "5 MP frame. 0: off")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 255.0));
  command->add_flag("--no-lost-spots", flags->no_lost_spots,
                    "Do not look for the spots the binariser missed where the lattice of the "
                    "frame's points puts them (dark patches, black walls; about 1 ms per 5 MP "
                    "frame)");
  command->add_flag("--no-cut-spots", flags->no_cut_spots,
                    "Keep the spots a depth step cut (smaller than their neighbours where these "
                    "straddle a step: their centre lies off the element's, at a joint's edge up "
                    "to millimetres)");
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
