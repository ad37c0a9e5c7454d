// `sewer3d describe`: loads and validates a module file and reports what it describes; with
// --rig, how six such modules on the carrier cover the pipe wall.

#include <fmt/core.h>

#include <algorithm>
#include <cstdio>
#include <string>

#include "sewer3d/cli/command.hpp"
#include "sewer3d/cli/exit_code.hpp"
#include "sewer3d/cli/summary.hpp"
#include "sewer3d/io/module_io.hpp"
#include "sewer3d/sim/rig.hpp"

namespace sewer3d::cli {
namespace {

// The worst overlap of the table: where neighbouring modules leave the widest gap (or overlap
// least) — which DN, carrier offset, and whether in texture or 3-D.
struct WorstOverlap {
  double deg = 1e9, mm = 0.0, dn = 0.0;
  Eigen::Vector2d offset = Eigen::Vector2d::Zero();
  bool lit = false;
};

// Prints the rig's overlap table; returns its worst case.
WorstOverlap PrintRigOverlap(const ModuleDescription& module) {
  WorstOverlap worst;
  const Rig rig = MakeRig(module, {});
  fmt::print(
      "\nrig: {} modules on a carrier Ø{:.0f} x {:.0f} mm, cameras and projectors on its axis\n",
      rig.modules.size(), rig.carrier_diameter_mm, rig.carrier_length_mm);
  for (const RigModule& m : rig.modules) {
    fmt::print("  {} at {:>4.1f} h: camera at z {:+7.1f} mm, projector at z {:+7.1f} mm\n", m.name,
               m.clock_h, m.carrier_from_camera.translation.z(), ProjectorCentreInCarrier(m).z());
  }
  fmt::print("\nsmallest / largest overlap between neighbouring modules around the pipe\n");
  fmt::print("(texture: camera fields; 3-D: where camera and projector both reach)\n");
  fmt::print("  {:<6} {:<22} {:>22} {:>22}\n", "pipe", "carrier offset (x, y)", "texture deg (mm)",
             "3-D deg (mm)");
  const int step = std::max(1, module.camera.width / 160);  // ~160 x 120 rays a module
  for (const double dn : {200.0, 300.0, 400.0}) {
    for (const Eigen::Vector2d& offset : {Eigen::Vector2d(0, 0), Eigen::Vector2d(0, 25),
                                          Eigen::Vector2d(25, 0), Eigen::Vector2d(17.7, 17.7)}) {
      std::string cells;
      for (const bool lit : {false, true}) {
        const auto o = NeighbourOverlaps(rig, dn, offset, lit, step);
        const auto [lo, hi] = std::minmax_element(
            o.begin(), o.end(),
            [](const auto& a, const auto& b) { return a.overlap_deg < b.overlap_deg; });
        if (lo->overlap_deg < worst.deg) worst = {lo->overlap_deg, lo->overlap_mm, dn, offset, lit};
        cells += fmt::format(" {:>5.1f}-{:<4.1f} ({:>3.0f}-{:<3.0f})", lo->overlap_deg,
                             hi->overlap_deg, lo->overlap_mm, hi->overlap_mm);
      }
      fmt::print("  DN{:<4.0f} ({:+5.1f}, {:+5.1f}) mm        {}\n", dn, offset.x(), offset.y(),
                 cells);
    }
  }
  return worst;
}

// One warning line when six such modules leave part of the wall unseen; true then.
bool WarnOfGaps(const WorstOverlap& w) {
  if (w.deg >= 0.0) return false;
  std::fflush(stdout);  // the table first
  fmt::print(stderr,
             "sewer3d: warning: --rig: six such modules leave gaps of up to {:.1f}° ({:.0f} mm) "
             "between neighbours in {} (DN{:.0f}, carrier offset {:.1f}, {:.1f} mm): that part "
             "of the wall is never measured\n",
             -w.deg, -w.mm, w.lit ? "3-D" : "texture", w.dn, w.offset.x(), w.offset.y());
  return true;
}

}  // namespace

Command AddDescribeCommand(CLI::App& app) {
  auto module_path = std::make_shared<std::string>();
  auto rig = std::make_shared<bool>(false);
  CLI::App* sub = app.add_subcommand(
      "describe", "Validate a module.json and print its geometry, disparity range and pattern");
  sub->add_option("--module", *module_path, "module.json to check")->required();
  sub->add_flag(
      "--rig", *rig,
      "Also place six such modules on the carrier and report their overlap for DN200-DN400");
  return {sub, [module_path, rig] {
            const LoadedModule loaded = LoadModule(*module_path);
            fmt::print("{}: read\n", *module_path);
            const std::string problem = PrintModuleSummary(loaded.module, loaded.pattern);
            bool gaps = false;
            try {
              gaps = *rig && WarnOfGaps(PrintRigOverlap(loaded.module));
            } catch (const InvalidValue& e) {  // the module's geometry, not a flag's value
              std::fflush(stdout);
              fmt::print(stderr, "sewer3d: error: {}: --rig: {}\n", *module_path, e.problem());
              return static_cast<int>(kExitBadFile);
            }
            if (problem.empty()) {
              fmt::print("{}: {}\n", *module_path,
                         gaps ? "a valid module, but six on the carrier do not cover the pipe "
                                "all around"
                              : "a valid, usable module");
              return 0;
            }
            std::fflush(stdout);
            fmt::print(stderr, "sewer3d: error: {}: {}\n", *module_path, problem);
            return 1;
          }};
}

}  // namespace sewer3d::cli
