// RejectDepthOutliers on points laid out by hand: the per-point median test and the removal of
// small surface segments (a spot group decoded with a wrong tile); RejectSharedElements.

#include <gtest/gtest.h>

#include <algorithm>
#include <utility>
#include <vector>

#include "sewer3d/triangulate/correspondences.hpp"

namespace sewer3d {
namespace {

struct Layout {
  std::vector<TriangulatedPoint> points;
  std::vector<CodedObservation> observations;
  // `label` goes into the element's row (the tests' labels: 0 wall, 1 deep patch, 2 wrong
  // group), `col` into its column.
  void Add(double u, double v, double z, int label, int col = 0) {
    CodedObservation o;
    o.camera_px = {u, v};
    observations.push_back(o);
    TriangulatedPoint p;
    p.observation = static_cast<int>(points.size());
    p.point_mm = {0.0, 0.0, z};
    p.row = label;
    p.col = col;
    points.push_back(p);
  }
  int Count(const std::vector<TriangulatedPoint>& kept, int label) const {
    int n = 0;
    for (const TriangulatedPoint& p : kept) n += p.row == label;
    return n;
  }
};

// A wall of spots 20 px apart at 150 mm (a gentle ramp), with a 6 x 6 patch 60 mm deeper (a
// bore seen through a connection) and, in a 5 x 5 hole without decodes, four spots 60 mm off
// 6 px apart: each is the others' only neighbour within 30 px, so the median test keeps them.
Layout Wall() {
  Layout l;
  for (int r = 0; r < 30; ++r) {
    for (int c = 0; c < 40; ++c) {
      const bool hole = r >= 12 && r < 17 && c >= 28 && c < 33;
      const bool deep = r >= 5 && r < 11 && c >= 5 && c < 11;
      if (!hole) l.Add(20.0 * c, 20.0 * r, 150.0 + 0.05 * c + (deep ? 60.0 : 0.0), deep ? 1 : 0);
    }
  }
  for (const auto& [du, dv] : {std::pair(0.0, 0.0), {6.0, 0.0}, {0.0, 6.0}, {6.0, 6.0}})
    l.Add(600.0 + du, 280.0 + dv, 210.0, 2);
  return l;
}

TEST(RejectDepthOutliers, RemovesASmallWrongGroupAndKeepsADeepPatch) {
  Layout l = Wall();
  const int walls = l.Count(l.points, 0);
  std::vector<TriangulatedPoint> points = l.points;
  const int removed = RejectDepthOutliers(points, l.observations);
  EXPECT_EQ(l.Count(points, 2), 0);
  EXPECT_EQ(l.Count(points, 0), walls);
  // The patch loses its four corners (each sees 3 patch and 5 wall neighbours); the rest stays.
  EXPECT_EQ(l.Count(points, 1), 32);
  EXPECT_EQ(removed, 4 + 4);

  DepthOutlierOptions without;
  without.min_segment_points = 0;
  points = l.points;
  RejectDepthOutliers(points, l.observations, without);
  EXPECT_EQ(l.Count(points, 2), 4);  // the median test alone keeps the wrong group
}

TEST(RejectDepthOutliers, RefusesANegativeSegmentSize) {
  Layout l = Wall();
  DepthOutlierOptions options;
  options.min_segment_points = -1;
  EXPECT_THROW(RejectDepthOutliers(l.points, l.observations, options), std::invalid_argument);
}

// Two spots decoded as one element (a label slipped across a joint's step): both go, every
// other point stays, in its order.
TEST(RejectSharedElements, RemovesEveryClaimOfAnElementClaimedTwice) {
  std::vector<TriangulatedPoint> points(6);
  const int elements[6][2] = {{19, 30}, {19, 31}, {20, 30}, {19, 30}, {-3, 30}, {19, -30}};
  for (int i = 0; i < 6; ++i) {
    points[i].observation = i;
    points[i].row = elements[i][0];
    points[i].col = elements[i][1];
  }
  EXPECT_EQ(RejectSharedElements(points), 2);
  ASSERT_EQ(points.size(), 4u);
  EXPECT_EQ(points[0].observation, 1);
  EXPECT_EQ(points[1].observation, 2);
  EXPECT_EQ(points[2].observation, 4);
  EXPECT_EQ(points[3].observation, 5);
  EXPECT_EQ(RejectSharedElements(points), 0);
}

// A wall of spots, each its own element, and one wrong spot between them 60 mm deeper that
// claims the element of a wall spot: the depth test removes it first, so the wall spot keeps
// its point; shared elements judged first would remove both.
TEST(RejectInconsistentPoints, AWrongClaimThatIsADepthOutlierCostsNoGoodPoint) {
  Layout l;  // each point's element: (r, c)
  for (int r = 0; r < 20; ++r)
    for (int c = 0; c < 20; ++c) l.Add(20.0 * c, 20.0 * r, 150.0 + 0.05 * c, r, c);
  l.Add(210.0, 190.0, 210.0, 9, 10);  // between four wall spots; wall spot (9, 10) is at (200, 180)
  std::vector<TriangulatedPoint> kept = l.points;
  const InconsistentPoints removed = RejectInconsistentPoints(kept, l.observations);
  EXPECT_EQ(removed.depth_outliers, 1);
  EXPECT_EQ(removed.shared_elements, 0);
  ASSERT_EQ(kept.size(), 400u);
  EXPECT_TRUE(std::all_of(kept.begin(), kept.end(),
                          [](const TriangulatedPoint& p) { return p.point_mm.z() < 200.0; }));
  kept = l.points;
  EXPECT_EQ(RejectSharedElements(kept), 2);  // the other order: the wall spot goes too
}

}  // namespace
}  // namespace sewer3d
