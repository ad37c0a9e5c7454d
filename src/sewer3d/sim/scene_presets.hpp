#pragma once
/// \file
/// The built-in scenes' content (`simulate frame --scene pipe-wall`, docs/simulator.md).

#include <vector>

#include "sewer3d/sim/pipe_feature.hpp"

namespace sewer3d {

/// The pipe-wall preset's features: a displaced open joint, an intrusion (bump), a pit and a
/// crack, placed for a DN300 wall seen by the default module, all inside its field of view.
std::vector<PipeFeature> PipeWallPresetFeatures();

}  // namespace sewer3d
