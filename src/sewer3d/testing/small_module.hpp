#pragma once
/// \file
/// The default module at a reduced camera size for tests: the same angles and lens as the
/// full 2592 x 1944 module, (2592 / width)² fewer pixels.

#include "sewer3d/camera/default_module.hpp"
#include "sewer3d/camera/module.hpp"

namespace sewer3d::testing {

/// The default module with a `width` x `width` · 3/4 camera (projector scaled alike).
ModuleDescription SmallDefaultModule(int width = 648);

}  // namespace sewer3d::testing
