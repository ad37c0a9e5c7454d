#pragma once
/// \file
/// Point clouds as PLY (DESIGN.md contract): binary little-endian, float x y z in mm, uchar
/// red green blue when colours are given.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace sewer3d {

/// The frames a sewer3d PLY names in its header: a module's camera (reconstruct, rgbd) or the
/// model frame (WS/model/surface.ply).
inline constexpr const char* kCameraFrame = "camera frame";
inline constexpr const char* kModelFrame = "model frame";

/// `colours` is empty or one RGB per point; `frame` names the points' frame in the header's
/// comment ("comment sewer3d, mm, camera frame").
void WritePly(const std::filesystem::path& path, const std::vector<Eigen::Vector3d>& points,
              const std::vector<std::array<std::uint8_t, 3>>& colours,
              const std::string& frame = kCameraFrame);

/// Reads x y z of a PLY's vertices: ASCII or binary (either byte order), any scalar type
/// (char … double). FileError for a malformed header, a count the body does not match, a
/// list property in the vertex element, or a file that is not a regular file. `frame`, when
/// given, receives the frame sewer3d's comment names (empty for a file without one).
std::vector<Eigen::Vector3d> ReadPlyPoints(const std::filesystem::path& path,
                                           std::string* frame = nullptr);

}  // namespace sewer3d
