#pragma once
/// \file
/// Checks of the raw command line before CLI11 parses it: mistakes CLI11 would report as
/// something else (a missing option) or not at all (an option taken as another's value).

#include <CLI/CLI.hpp>
#include <string>

namespace sewer3d::cli {

/// The first argument written as a long option with one dash ("-out"), which CLI11 would read
/// as the short flags -o -u -t and then report --out as missing; empty when none.
std::string SingleDashLongOption(const CLI::App& app, int argc, char** argv);

/// "unknown option --modul (did you mean --module?)" for the first long option no command
/// has (CLI11 would first report a required option as missing); empty when none.
std::string UnknownLongOption(const CLI::App& app, int argc, char** argv);

/// Why an option that takes a value is followed by another option's name ("--out --quiet",
/// which CLI11 would take as a folder named --quiet); empty when none is.
std::string FlagGivenAsValue(const CLI::App& app, int argc, char** argv);

}  // namespace sewer3d::cli
