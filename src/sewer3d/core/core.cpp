// The core module is header-only today; this unit anchors the static library target.
#include "sewer3d/core/check.hpp"
#include "sewer3d/core/rigid3.hpp"
