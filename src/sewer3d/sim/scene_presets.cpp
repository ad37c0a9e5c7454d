#include "sewer3d/sim/scene_presets.hpp"

namespace sewer3d {

std::vector<PipeFeature> PipeWallPresetFeatures() {
  using T = PipeFeature::Type;
  // Clock positions in hours, 12 h = 360° (so −18° is −18 / 30 h) from the view direction.
  return {{.type = T::kJointStep,
           .station_mm = 45.0,
           .clock_h = 0.0,
           .depth_mm = 4.0,
           .gap_mm = 6.0,
           .offset_mm = 5.0},
          {.type = T::kBump,
           .station_mm = 10.0,
           .clock_h = -18.0 / 30.0,
           .height_mm = 6.0,
           .radius_mm = 6.0},
          {.type = T::kPit,
           .station_mm = 0.0,
           .clock_h = 15.0 / 30.0,
           .depth_mm = 4.0,
           .radius_mm = 10.0},
          {.type = T::kCrack,
           .station_mm = 90.0,
           .clock_h = -5.0 / 30.0,
           .length_mm = 60.0,
           .width_mm = 1.0,
           .depth_mm = 2.0,
           .angle_deg = 70.0}};
}

}  // namespace sewer3d
