#include "sewer3d/inspect/observation.hpp"

#include <cmath>

namespace sewer3d {

bool Quantity::Measured() const { return std::isfinite(value); }

const Quantity* Observation::Find(const std::string& name) const {
  for (const Quantity& q : quantities) {
    if (q.name == name) return &q;
  }
  return nullptr;
}

bool IsContinuous(const Observation& o) { return o.code == "BAA" || o.code == "BBC"; }

}  // namespace sewer3d
