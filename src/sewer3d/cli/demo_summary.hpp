#pragma once
/// \file
/// What `sewer3d demo` prints at its end (cli/cmd_demo.cpp): its peak memory and the files to
/// look at.

#include <filesystem>

namespace sewer3d::cli {

/// The process's peak resident memory so far, GB.
double PeakMemoryGb();

/// The files of the demo folder `dir` to look at, each with what it shows, the report `html`
/// first.
void PrintLookAt(const std::filesystem::path& dir, const std::filesystem::path& html);

}  // namespace sewer3d::cli
