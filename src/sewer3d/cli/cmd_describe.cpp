// `sewer3d describe`: loads and validates a module file and reports what it describes.

#include <fmt/core.h>

#include "sewer3d/cli/command.hpp"
#include "sewer3d/cli/summary.hpp"
#include "sewer3d/io/module_io.hpp"

namespace sewer3d::cli {

Command AddDescribeCommand(CLI::App& app) {
  auto module_path = std::make_shared<std::string>();
  CLI::App* sub = app.add_subcommand(
      "describe", "Validate a module.json and print its geometry, disparity range and pattern");
  sub->add_option("--module", *module_path, "module.json to check")->required();
  return {sub, [module_path] {
            const LoadedModule loaded = LoadModule(*module_path);
            fmt::print("{}: valid module file\n", *module_path);
            return PrintModuleSummary(loaded.module, loaded.pattern) ? 0 : 1;
          }};
}

}  // namespace sewer3d::cli
