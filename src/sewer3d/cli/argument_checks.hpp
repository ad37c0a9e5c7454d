#pragma once
/// \file
/// Checks of the command line that CLI11 does not make, run by main before a command starts.

#include <CLI/CLI.hpp>
#include <filesystem>
#include <string>
#include <utility>

namespace sewer3d {
struct FrameReconstructionOptions;
}  // namespace sewer3d

namespace sewer3d::cli {

/// The first option or argument of the chosen subcommands given as an empty string ("" names
/// no file and no value) or as NaN (ranges never refuse it), with what is wrong; nullptr when
/// none.
std::pair<const CLI::Option*, const char*> BadValue(const CLI::App& app);

/// Whether the option that a CLI11 message starts with ("--rows: …") takes whole numbers,
/// looked up in the chosen subcommands.
bool TakesWholeNumbers(const CLI::App& app, const std::string& message);

/// What a missing positional argument or subcommand of the deepest chosen subcommand is for
/// ("evaluate needs its KIND argument: plane, cylinder, …"), in place of CLI11's "KIND is
/// required" or "A subcommand is required"; empty for any other message.
std::string MissingArgument(const CLI::App& app, const std::string& message);

/// A CLI11 check that a file name to write ends in `extension` (".png") and has a stem; its
/// refusal says why (`why`: "the matrix is written losslessly as PNG").
/// The spot-finding flags of the commands that decode pattern images.
struct SpotFlags {
  double faint_spots = 0.0;    ///< `--faint-spots LEVELS`: NiblackOptions::min_contrast_3x3
  bool no_lost_spots = false;  ///< `--no-lost-spots`: LostSpotOptions::enabled off
  bool no_cut_spots = false;   ///< `--no-cut-spots`: CutSpotOptions::enabled off
  void ApplyTo(FrameReconstructionOptions& options) const;
};

/// Adds `--faint-spots LEVELS` and `--no-lost-spots` to a command that decodes pattern images.
void AddSpotFlags(CLI::App* command, SpotFlags* flags);

CLI::Validator FileNameEnding(const std::string& extension, const std::string& why);

/// Throws InvalidValue naming `flag` when `folder` is a capture run's folder or a processing
/// workspace, or lies inside one (a run.json or workspace.json there or above): outputs there
/// would mix with the run as captured, or replace a stage's files behind the workspace's record.
void CheckNotInRunOrWorkspace(const std::filesystem::path& folder, const char* flag);
/// CheckNotInRunOrWorkspace for the folder an output file `file` goes to (the working folder for a
/// bare name).
void CheckFileNotInRunOrWorkspace(const std::filesystem::path& file, const char* flag);

/// Throws InvalidValue naming --out when `out` is the pattern.png beside a module.json or a
/// rig.json: it is their pattern matrix, and a new pattern written over it would make the module
/// another one, its calibration no longer true.
void CheckNotAModulesMatrix(const std::filesystem::path& out);

/// Throws InvalidValue naming `flag` when the existing file `out` is a module description
/// (module.json, or JSON with a "projector"): a result of another kind written over it would
/// lose the module. `writes` says what the command writes ("a camera calibration").
void CheckNotAModuleFile(const std::filesystem::path& out, const char* flag,
                         const std::string& writes);

/// Throws FileError when the workspace `folder` of a stage that continues one (`stage`:
/// register, model, inspect, report) does not exist, before anything creates it: a mistyped
/// --out gets an error and no new folder.
void CheckWorkspaceExists(const std::filesystem::path& folder, const std::string& stage);

/// Throws InvalidValue naming --out unless the demo's folder `dir` can hold a run and a
/// workspace of its own: not a file, not inside a capture run (whose folder must stay as
/// captured) or a workspace (whose --force would remove it), and no workspace of another run
/// at dir/ws (refused only after the simulation otherwise).
void CheckDemoFolder(const std::filesystem::path& dir);

}  // namespace sewer3d::cli
