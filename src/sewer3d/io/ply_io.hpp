#pragma once
/// \file
/// Point clouds as PLY (DESIGN.md contract): binary little-endian, float x y z in mm, uchar
/// red green blue when colours are given.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <filesystem>
#include <vector>

namespace sewer3d {

/// `colours` is empty or one RGB per point.
void WritePly(const std::filesystem::path& path, const std::vector<Eigen::Vector3d>& points,
              const std::vector<std::array<std::uint8_t, 3>>& colours);

/// Reads x y z of a PLY's vertices: ASCII or binary (either byte order), any scalar type
/// (char … double). FileError for a malformed header, a count the body does not match, a
/// list property in the vertex element, or a file that is not a regular file.
std::vector<Eigen::Vector3d> ReadPlyPoints(const std::filesystem::path& path);

}  // namespace sewer3d
