#pragma once
/// \file
/// GoogleTest matchers with tolerances in physical units, shared by every module's tests.

#include <gmock/gmock.h>

#include <cmath>
#include <ostream>

#include "sewer3d/core/rigid3.hpp"
#include "sewer3d/core/units.hpp"

namespace sewer3d::testing {

/// Rotation angle between two poses' rotations, degrees.
inline double RotationErrorDeg(const Rigid3d& a, const Rigid3d& b) {
  return a.rotation.angularDistance(b.rotation) * kDegPerRad;
}

/// Distance between two poses' translations, mm.
inline double TranslationErrorMm(const Rigid3d& a, const Rigid3d& b) {
  return (a.translation - b.translation).norm();
}

/// Matches a Rigid3d within `rot_deg` of rotation and `trans_mm` of translation of `expected`:
/// EXPECT_THAT(estimate, PoseNear(truth, 0.01, 0.05)).
MATCHER_P3(PoseNear, expected, rot_deg, trans_mm,
           "is within " + ::testing::PrintToString(rot_deg) + " deg and " +
               ::testing::PrintToString(trans_mm) + " mm of the expected pose") {
  const double rot = RotationErrorDeg(arg, expected);
  const double trans = TranslationErrorMm(arg, expected);
  *result_listener << "rotation off by " << rot << " deg, translation by " << trans << " mm";
  return rot <= rot_deg && trans <= trans_mm;
}

}  // namespace sewer3d::testing
