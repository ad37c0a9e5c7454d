#include "sewer3d/register/module_agreement.hpp"

#include <algorithm>
#include <map>
#include <optional>
#include <utility>

#include "sewer3d/core/check.hpp"

namespace sewer3d {

namespace {

/// The pairwise edges tallied per key (`key` of the two modules; nullopt: not counted).
template <typename Key>
std::vector<ModulePairAgreement> Tally(const std::vector<AcquisitionNode>& nodes,
                                       const std::vector<RegistrationEdge>& edges,
                                       const FusionResult& fused, const Key& key) {
  SEWER3D_VALIDATE(
      fused.accepted.size() == edges.size(), "fused",
      "has " << fused.accepted.size() << " edges' outcomes for " << edges.size() << " edges");
  SEWER3D_VALIDATE(
      fused.world_from_camera.size() == nodes.size(), "fused",
      "has " << fused.world_from_camera.size() << " poses for " << nodes.size() << " nodes");
  std::map<std::pair<int, int>, ModulePairAgreement> pairs;
  std::map<std::pair<int, int>, std::vector<double>> offsets;
  const int n = static_cast<int>(nodes.size());
  for (size_t k = 0; k < edges.size(); ++k) {
    const RegistrationEdge& e = edges[k];
    if (!IsPairwiseEdge(e.type)) continue;
    SEWER3D_VALIDATE(e.a >= 0 && e.a < n && e.b >= 0 && e.b < n, "edges",
                     "edge " << e.a << " → " << e.b << " with " << n << " nodes");
    const std::optional<std::pair<int, int>> which = key(nodes[e.a].module, nodes[e.b].module);
    if (!which) continue;
    ModulePairAgreement& p = pairs[*which];
    p.module_a = which->first;
    p.module_b = which->second;
    ++p.edges;
    if (fused.accepted[k]) continue;
    ++p.rejected;
    PoseEdge pose_edge;
    pose_edge.a_from_b = e.a_from_b;
    const Vector6d r =
        EdgeResidual(pose_edge, fused.world_from_camera[e.a], fused.world_from_camera[e.b]);
    offsets[*which].push_back(r.head<3>().norm());
  }
  std::vector<ModulePairAgreement> out;
  for (auto& [which, p] : pairs) {
    std::vector<double>& v = offsets[which];
    if (!v.empty()) {
      std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
      p.median_rejected_offset_mm = v[v.size() / 2];
    }
    out.push_back(p);
  }
  return out;
}

}  // namespace

std::vector<ModulePairAgreement> ModulePairAgreements(const std::vector<AcquisitionNode>& nodes,
                                                      const std::vector<RegistrationEdge>& edges,
                                                      const FusionResult& fused) {
  return Tally(nodes, edges, fused, [](int a, int b) -> std::optional<std::pair<int, int>> {
    if (a == b) return std::nullopt;
    return std::minmax(a, b);
  });
}

ModulePairAgreement AlongAgreement(const std::vector<AcquisitionNode>& nodes,
                                   const std::vector<RegistrationEdge>& edges,
                                   const FusionResult& fused) {
  const std::vector<ModulePairAgreement> all =
      Tally(nodes, edges, fused, [](int a, int b) -> std::optional<std::pair<int, int>> {
        if (a != b) return std::nullopt;
        return std::make_pair(-1, -1);
      });
  if (!all.empty()) return all.front();
  ModulePairAgreement none;
  none.module_a = none.module_b = -1;
  return none;
}

bool Disagrees(const ModulePairAgreement& pair, int min_rejected, double min_fraction,
               double min_offset_mm) {
  return pair.rejected >= min_rejected &&
         pair.rejected >= min_fraction * static_cast<double>(pair.edges) &&
         pair.median_rejected_offset_mm >= min_offset_mm;
}

}  // namespace sewer3d
