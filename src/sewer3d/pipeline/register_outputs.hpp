#pragma once
/// \file
/// The registration stage's outputs (internal to register_stage.cpp): poses.csv, graph.g2o
/// (vertex id = module · 10⁶ + counter), edges.csv, report.json and graph.png in WS/registration.

#include <filesystem>
#include <string>
#include <vector>

#include "sewer3d/register/fusion.hpp"
#include "sewer3d/run/rig.hpp"

namespace sewer3d {

void WriteRegistrationOutputs(const std::filesystem::path& folder, const Rig& rig,
                              const std::vector<AcquisitionNode>& nodes,
                              const std::vector<RegistrationEdge>& edges, const FusionResult& fused,
                              double length_scale_mm, const std::string& report_json);

}  // namespace sewer3d
