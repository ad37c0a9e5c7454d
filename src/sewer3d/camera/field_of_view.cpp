#include "sewer3d/camera/field_of_view.hpp"

#include <cmath>

#include "sewer3d/core/units.hpp"

namespace sewer3d {

double FieldOfViewDeg(const CameraModel& model, bool horizontal) {
  const auto& c = model.intrinsics();
  const auto a = horizontal ? model.Unproject({-0.5, c.cy}) : model.Unproject({c.cx, -0.5});
  const auto b =
      horizontal ? model.Unproject({c.width - 0.5, c.cy}) : model.Unproject({c.cx, c.height - 0.5});
  if (!a || !b) return std::nan("");
  return RadToDeg(horizontal ? std::atan(b->x()) - std::atan(a->x())
                             : std::atan(b->y()) - std::atan(a->y()));
}

}  // namespace sewer3d
