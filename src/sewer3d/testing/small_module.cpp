#include "sewer3d/testing/small_module.hpp"

namespace sewer3d::testing {

ModuleDescription SmallDefaultModule(int width) {
  DefaultModuleOptions options;
  options.camera_width = width;
  options.camera_height = width * 3 / 4;
  return MakeDefaultModule(options);
}

}  // namespace sewer3d::testing
