#include "sewer3d/inspect/observation.hpp"

namespace sewer3d {

const Quantity* Observation::Find(const std::string& name) const {
  for (const Quantity& q : quantities) {
    if (q.name == name) return &q;
  }
  return nullptr;
}

bool IsContinuous(const Observation& o) { return o.code == "BAA" || o.code == "BBC"; }

}  // namespace sewer3d
