#include "sewer3d/register/module_agreement.hpp"

#include <algorithm>
#include <map>
#include <utility>

#include "sewer3d/core/check.hpp"

namespace sewer3d {

std::vector<ModulePairAgreement> ModulePairAgreements(const std::vector<AcquisitionNode>& nodes,
                                                      const std::vector<RegistrationEdge>& edges,
                                                      const FusionResult& fused) {
  SEWER3D_VALIDATE(fused.accepted.size() == edges.size(), "fused",
                   "has " << fused.accepted.size() << " edges' outcomes for " << edges.size()
                          << " edges");
  SEWER3D_VALIDATE(fused.world_from_camera.size() == nodes.size(), "fused",
                   "has " << fused.world_from_camera.size() << " poses for " << nodes.size()
                          << " nodes");
  std::map<std::pair<int, int>, ModulePairAgreement> pairs;
  std::map<std::pair<int, int>, std::vector<double>> offsets;
  const int n = static_cast<int>(nodes.size());
  for (size_t k = 0; k < edges.size(); ++k) {
    const RegistrationEdge& e = edges[k];
    if (!IsPairwiseEdge(e.type)) continue;
    SEWER3D_VALIDATE(e.a >= 0 && e.a < n && e.b >= 0 && e.b < n, "edges",
                     "edge " << e.a << " → " << e.b << " with " << n << " nodes");
    const int ma = nodes[e.a].module, mb = nodes[e.b].module;
    if (ma == mb) continue;
    const std::pair<int, int> key = std::minmax(ma, mb);
    ModulePairAgreement& p = pairs[key];
    p.module_a = key.first;
    p.module_b = key.second;
    ++p.edges;
    if (fused.accepted[k]) continue;
    ++p.rejected;
    PoseEdge pose_edge;
    pose_edge.a_from_b = e.a_from_b;
    const Vector6d r =
        EdgeResidual(pose_edge, fused.world_from_camera[e.a], fused.world_from_camera[e.b]);
    offsets[key].push_back(r.head<3>().norm());
  }
  std::vector<ModulePairAgreement> out;
  for (auto& [key, p] : pairs) {
    std::vector<double>& v = offsets[key];
    if (!v.empty()) {
      std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
      p.median_rejected_offset_mm = v[v.size() / 2];
    }
    out.push_back(p);
  }
  return out;
}

bool DisagreesWithRig(const ModulePairAgreement& pair, int min_rejected, double min_fraction,
                      double min_offset_mm) {
  return pair.rejected >= min_rejected &&
         pair.rejected >= min_fraction * static_cast<double>(pair.edges) &&
         pair.median_rejected_offset_mm >= min_offset_mm;
}

}  // namespace sewer3d
