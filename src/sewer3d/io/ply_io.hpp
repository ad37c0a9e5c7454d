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

/// Reads x y z (float or double, binary little-endian or ASCII) of a PLY's vertices.
std::vector<Eigen::Vector3d> ReadPlyPoints(const std::filesystem::path& path);

}  // namespace sewer3d
