#pragma once
/// \file
/// g2o pose graphs (DESIGN.md, pose-graph contract): VERTEX_SE3:QUAT id x y z qx qy qz qw,
/// EDGE_SE3:QUAT a b x y z qx qy qz qw followed by the 21 upper-triangular entries of the 6x6
/// information matrix (row by row), and FIX id. Errors are FileError "PATH: line N: ...".

#include <filesystem>

#include "sewer3d/posegraph/pose_graph.hpp"

namespace sewer3d {

/// Reads a graph. Rejects malformed lines, non-finite numbers, zero or far-from-unit
/// quaternions (|‖q‖ − 1| > 1e-3; nearer ones, written with few digits, are normalised),
/// information that is not symmetric positive definite, duplicate vertices, edges naming a
/// vertex the file does not define, and unknown elements.
PoseGraph ReadG2o(const std::filesystem::path& path);

/// Writes a graph with round-trip precision.
void WriteG2o(const std::filesystem::path& path, const PoseGraph& graph);

}  // namespace sewer3d
