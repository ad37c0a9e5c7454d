// `sewer3d pattern`: searches a perfect-submap spot array and writes it with its report.

#include <fmt/core.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "sewer3d/cli/argument_checks.hpp"
#include "sewer3d/cli/command.hpp"
#include "sewer3d/cli/flag_names.hpp"
#include "sewer3d/core/check.hpp"
#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/io/image_io.hpp"
#include "sewer3d/io/pattern_io.hpp"
#include "sewer3d/pattern/default_pattern.hpp"
#include "sewer3d/pattern/submap_search.hpp"

namespace sewer3d::cli {

Command AddPatternCommand(CLI::App& app) {
  struct Args {
    std::string out;
    SubmapSearchOptions search = DefaultPatternSearchOptions();
    bool plain = false;
    bool allow_adjacent = false;
    bool quiet = false;
    double max_moves = 0.0;  ///< read as a number so that 1e15 is accepted; whole (checked)
  };
  auto args = std::make_shared<Args>();
  CLI::App* sub = app.add_subcommand(
      "pattern", "Search a perfect-submap spot array (Morano et al.) and write it as a PNG");
  auto& s = args->search;
  sub->add_option("--out", args->out, "Matrix PNG to write; a .json report goes beside it")
      ->required()
      // The matrix must survive exactly: a lossy format would change spots.
      ->check(FileNameEnding(".png", "the matrix is written losslessly as PNG"));
  sub->add_option("--window", s.constraints.window, "Codeword window side, elements")
      ->capture_default_str()
      ->check(CLI::Range(2, 8));
  sub->add_option("--min-hamming", s.constraints.min_hamming,
                  "Minimum Hamming distance between any two windows")
      ->capture_default_str()
      ->check(CLI::Range(1, 64));
  sub->add_option("--min-weight", s.constraints.min_weight, "Minimum spots per window")
      ->capture_default_str()
      ->check(CLI::Range(0, 64));
  sub->add_option("--rows", s.rows, "Array rows (across the epipolar direction)")
      ->capture_default_str()
      ->check(CLI::Range(2, 4096));
  sub->add_option("--cols", s.cols, "Array columns (along the epipolar direction)")
      ->capture_default_str()
      ->check(CLI::Range(2, 4096));
  sub->add_option("--seed", s.seed, "Random seed (the search is deterministic for a seed)")
      ->check(Digits())
      ->capture_default_str();
  args->max_moves = static_cast<double>(s.max_moves);
  sub->add_option("--max-moves", args->max_moves, "Give up after this many moves")
      ->capture_default_str()
      ->check(CLI::Range(1.0, 1e15))
      ->check(CLI::Validator(
          [](const std::string& text) {
            const double v = std::strtod(text.c_str(), nullptr);
            return v == std::floor(v) ? std::string() : "expected a whole number, got " + text;
          },
          "", "whole"));
  sub->add_option("--max-seconds", s.max_seconds, "Give up after this many seconds (0: no limit)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1e7));
  sub->add_flag("--plain", args->plain,
                "Windows only inside the array, not wrapping around its edges (not a torus)");
  sub->add_flag("--allow-adjacent", args->allow_adjacent, "Allow 8-adjacent spots");
  sub->add_flag("--quiet", args->quiet, "No progress output");
  return {sub, [args] {
            auto options = args->search;
            options.max_moves = static_cast<std::int64_t>(args->max_moves);
            options.constraints.torus = !args->plain;
            options.constraints.isolated = !args->allow_adjacent;
            if (!args->quiet) {
              options.progress_interval_moves = 2000;
              options.progress = [](const SubmapSearchProgress& p) {
                std::fprintf(stderr, "\rsearch: %8.1f s  %10lld moves  cost %5d  best %5d  ",
                             p.elapsed_s, static_cast<long long>(p.moves), p.cost, p.best_cost);
                return true;
              };
            }
            try {
              options.Check();
            } catch (const InvalidValue& e) {
              throw WithFlagNames(e, {{"min_weight", "--min-weight"},
                                      {"min_hamming", "--min-hamming"},
                                      {"window", "--window"},
                                      {"rows", "--rows"},
                                      {"cols", "--cols"},
                                      {"rows, cols", "--rows, --cols"},
                                      {"max_moves", "--max-moves"}});
            }
            // Both outputs checked before the search: a refusal leaves neither written.
            CheckFileNotInRunOrWorkspace(args->out, "--out");
            CheckNotAModulesMatrix(args->out);
            CheckOutputFile(args->out);
            CheckOutputFile(PatternSidecarPath(args->out));
            const char* kind = options.constraints.torus ? "torus" : "plain";
            fmt::print(
                "searching a {}x{} {} array: window {}, min Hamming {}, min weight {}, {}, "
                "seed {}\n",
                options.rows, options.cols, kind, options.constraints.window,
                options.constraints.min_hamming, options.constraints.min_weight,
                options.constraints.isolated ? "isolated spots" : "adjacent spots allowed",
                options.seed);
            std::fflush(stdout);
            const SubmapSearchResult result = SearchPerfectSubmap(options);
            if (options.progress) std::fprintf(stderr, "\n");
            // Verified only when reached: the check compares every pair of windows (seconds
            // for a large array) and an unreached one fails anyway.
            const PatternReport report =
                result.reached ? VerifyPattern(result.array, options.constraints) : PatternReport{};
            if (!result.reached || !report.valid) {
              const std::string best =
                  result.final_cost >= 0
                      ? fmt::format("best attempt: {} constraint violations", result.final_cost)
                      : "the budget ended while the search was being set up";
              fmt::print(stderr,
                         "sewer3d: error: {}x{} {} array not reached ({} after {} moves, {:.1f} s; "
                         "{}). Try fewer columns or rows, another seed, or a larger {}.\n",
                         options.rows, options.cols, kind, result.termination, result.moves,
                         result.elapsed_s, best,
                         result.termination == "time budget" ? "--max-seconds" : "--max-moves");
              return 1;
            }
            const std::filesystem::path out = args->out;
            WritePatternMatrix(out, result.array);
            WritePatternSidecar(PatternSidecarPath(out), {&options, &result, "search"}, report);
            fmt::print("reached in {} moves, {:.2f} s: {}\nwrote {} and {}\n", result.moves,
                       result.elapsed_s, Describe(report), out.string(),
                       PatternSidecarPath(out).string());
            return 0;
          }};
}

}  // namespace sewer3d::cli
