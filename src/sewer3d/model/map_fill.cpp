#include "sewer3d/model/map_fill.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <utility>
#include <vector>

#include "sewer3d/model/pipe_map.hpp"

namespace sewer3d {
namespace {

constexpr auto kNone = static_cast<unsigned char>(Coverage::kNone);
constexpr auto kMeasured = static_cast<unsigned char>(Coverage::kMeasured);

// One hole: its cells, found by a flood fill from a seed; `small` when it fits the limits.
struct Hole {
  std::vector<std::pair<int, int>> cells;
  bool small = true;
};

Hole FloodHole(const cv::Mat1b& coverage, cv::Mat1b& seen, int seed_row, int seed_col, int max_rows,
               int max_cols) {
  Hole hole;
  const int rows = coverage.rows, cols = coverage.cols;
  int row_lo = seed_row, row_hi = seed_row, col_lo = seed_col, col_hi = seed_col;
  // Stack of (row, unwrapped column): the extent across the clock seam is measured unwrapped.
  std::vector<std::pair<int, int>> stack{{seed_row, seed_col}};
  seen(seed_row, seed_col) = 1;
  while (!stack.empty()) {
    const auto [r, u] = stack.back();
    stack.pop_back();
    const int c = ((u % cols) + cols) % cols;
    hole.cells.emplace_back(r, c);
    row_lo = std::min(row_lo, r), row_hi = std::max(row_hi, r);
    col_lo = std::min(col_lo, u), col_hi = std::max(col_hi, u);
    if (r == 0 || r == rows - 1) hole.small = false;  // may go on beyond the grid
    const std::array<std::pair<int, int>, 4> next{{{r - 1, u}, {r + 1, u}, {r, u - 1}, {r, u + 1}}};
    for (const auto& [nr, nu] : next) {
      const int nc = ((nu % cols) + cols) % cols;
      if (nr < 0 || nr >= rows || seen(nr, nc) != 0 || coverage(nr, nc) != kNone) continue;
      seen(nr, nc) = 1;
      stack.emplace_back(nr, nu);
    }
  }
  if (row_hi - row_lo + 1 > max_rows || col_hi - col_lo + 1 > max_cols) hole.small = false;
  return hole;
}

}  // namespace

void FillSmallHoles(int max_rows, int max_cols, cv::Mat1f& displacement_mm, cv::Mat3f& colour,
                    cv::Mat1b& coverage) {
  const int rows = coverage.rows, cols = coverage.cols;
  cv::Mat1b seen(rows, cols, static_cast<unsigned char>(0));
  std::vector<Hole> small;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      if (coverage(r, c) != kNone || seen(r, c) != 0) continue;
      Hole hole = FloodHole(coverage, seen, r, c, max_rows, max_cols);
      if (hole.small) small.push_back(std::move(hole));
    }
  }
  // Interpolate from measured cells only (coverage is updated after all holes are filled).
  const int reach = std::max(max_rows, max_cols) + 1;
  for (const Hole& hole : small) {
    for (const auto& [r, c] : hole.cells) {
      double sum_w = 0.0, sum_d = 0.0;
      cv::Vec3d sum_c(0, 0, 0);
      const std::array<std::pair<int, int>, 4> directions{{{-1, 0}, {1, 0}, {0, -1}, {0, 1}}};
      for (const auto& [dr, dc] : directions) {
        for (int k = 1; k <= reach; ++k) {
          const int nr = r + k * dr, nc = (((c + k * dc) % cols) + cols) % cols;
          if (nr < 0 || nr >= rows) break;
          if (coverage(nr, nc) != kMeasured) continue;
          const double w = 1.0 / k;
          sum_w += w, sum_d += w * displacement_mm(nr, nc);
          sum_c += w * cv::Vec3d(colour(nr, nc));
          break;
        }
      }
      displacement_mm(r, c) = static_cast<float>(sum_d / sum_w);
      colour(r, c) = cv::Vec3f(sum_c / sum_w);
    }
  }
  for (const Hole& hole : small) {
    for (const auto& [r, c] : hole.cells)
      coverage(r, c) = static_cast<unsigned char>(Coverage::kFilled);
  }
}

void TrimHoleEdges(int band, const cv::Mat1b& frames, const cv::Mat1b& seen,
                   cv::Mat1f& displacement_mm, cv::Mat3f& colour, cv::Mat1b& coverage) {
  if (band <= 0 || coverage.empty()) return;
  const int rows = coverage.rows, cols = coverage.cols, pad = std::min(band, cols);
  // Columns wrapped by `pad` on both sides; rows padded with covered cells of no frame.
  const auto padded = [&](const cv::Mat1b& m, double rows_value) {
    cv::Mat1b out;
    cv::copyMakeBorder(m, out, 0, 0, pad, pad, cv::BORDER_WRAP);
    cv::copyMakeBorder(out, out, band, band, 0, 0, cv::BORDER_CONSTANT, cv::Scalar(rows_value));
    return out;
  };
  const cv::Mat1b covered = padded(coverage != 0, 255), framed = padded(frames, 0),
                  seeing = padded(seen, 0);
  cv::Mat1f to_hole;
  cv::distanceTransform(covered, to_hole, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  cv::Mat1b most;
  cv::dilate(framed, most, cv::getStructuringElement(cv::MORPH_RECT, {2 * band + 1, 2 * band + 1}));
  // Near a hole: kept by a majority of the frames that see it and measure around it, dropped
  // by a minority; a tie (half of them: between two frames' edges) goes to whichever of the
  // two it lies nearer, so that the edge falls halfway.
  enum : unsigned char { kKeep = 0, kDrop = 1, kTie = 2 };
  cv::Mat1b verdict(covered.size(), kKeep);
  for (int r = 0; r < covered.rows; ++r) {
    for (int c = 0; c < covered.cols; ++c) {
      if (covered(r, c) == 0) {
        verdict(r, c) = kDrop;
      } else if (to_hole(r, c) <= band) {
        const int twice = 2 * framed(r, c), local = std::min(seeing(r, c), most(r, c));
        verdict(r, c) = twice > local ? kKeep : twice < local ? kDrop : kTie;
      }
    }
  }
  cv::Mat1f to_kept, to_dropped;
  cv::distanceTransform(verdict != kKeep, to_kept, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  cv::distanceTransform(verdict != kDrop, to_dropped, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      const int pr = r + band, pc = c + pad;
      if (coverage(r, c) == 0 || verdict(pr, pc) == kKeep) continue;
      if (verdict(pr, pc) == kTie && to_kept(pr, pc) <= to_dropped(pr, pc)) continue;
      coverage(r, c) = 0;
      displacement_mm(r, c) = std::numeric_limits<float>::quiet_NaN();
      colour(r, c) = cv::Vec3f(0.0f, 0.0f, 0.0f);
    }
  }
}

}  // namespace sewer3d
