#include "sewer3d/inspect/components.hpp"

#include <algorithm>
#include <cmath>
#include <deque>

namespace sewer3d {

std::vector<MapComponent> HysteresisComponents(const cv::Mat1f& values, double sign, double low,
                                               double high) {
  cv::Mat1b levels = cv::Mat1b::zeros(values.rows, values.cols);
  for (int r = 0; r < values.rows; ++r) {
    for (int c = 0; c < values.cols; ++c) {
      const double v = sign * values(r, c);
      if (std::isfinite(v) && v >= low) levels(r, c) = v >= high ? 2 : 1;
    }
  }
  return HysteresisComponents(levels);
}

std::vector<MapComponent> HysteresisComponents(const cv::Mat1b& levels) {
  // 0 none, 1 candidate, 2 seed not yet taken, 3 taken.
  cv::Mat1b state = levels.clone();
  const int rows = levels.rows, cols = levels.cols;
  std::vector<MapComponent> out;
  std::deque<cv::Point> queue;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      if (state(r, c) != 2) continue;
      MapComponent comp;
      state(r, c) = 3;
      queue.emplace_back(c, r);
      while (!queue.empty()) {
        const cv::Point p = queue.front();
        queue.pop_front();
        comp.cells.push_back(p);
        for (int dr = -1; dr <= 1; ++dr) {
          for (int dc = -1; dc <= 1; ++dc) {
            const int nr = p.y + dr;
            if (nr < 0 || nr >= rows) continue;
            const int nc = ((p.x + dc) % cols + cols) % cols;
            if (state(nr, nc) != 1 && state(nr, nc) != 2) continue;
            state(nr, nc) = 3;
            queue.emplace_back(p.x + dc, nr);
          }
        }
      }
      comp.row_min = comp.row_max = comp.cells.front().y;
      comp.col_min = comp.col_max = comp.cells.front().x;
      for (const cv::Point& p : comp.cells) {
        comp.row_min = std::min(comp.row_min, p.y);
        comp.row_max = std::max(comp.row_max, p.y);
        comp.col_min = std::min(comp.col_min, p.x);
        comp.col_max = std::max(comp.col_max, p.x);
      }
      out.push_back(std::move(comp));
    }
  }
  return out;
}

}  // namespace sewer3d
