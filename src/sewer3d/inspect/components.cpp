#include "sewer3d/inspect/components.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <deque>
#include <numbers>
#include <numeric>
#include <set>

namespace sewer3d {

namespace {

void Bound(MapComponent& c) {
  c.row_min = c.row_max = c.cells.front().y;
  c.col_min = c.col_max = c.cells.front().x;
  for (const cv::Point& p : c.cells) {
    c.row_min = std::min(c.row_min, p.y);
    c.row_max = std::max(c.row_max, p.y);
    c.col_min = std::min(c.col_min, p.x);
    c.col_max = std::max(c.col_max, p.x);
  }
}

}  // namespace

double CellAxis::AngleDeg() const {
  const double angle = std::atan2(dir.y(), dir.x()) * 180.0 / std::numbers::pi;
  return angle <= -90.0 ? angle + 180.0 : angle;
}

CellAxis PrincipalAxis(const std::vector<cv::Point>& cells, double row_mm, double col_mm) {
  const auto mm = [&](const cv::Point& p) { return Eigen::Vector2d(p.y * row_mm, p.x * col_mm); };
  CellAxis a;
  for (const cv::Point& p : cells) a.centre += mm(p);
  a.centre /= static_cast<double>(cells.size());
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (const cv::Point& p : cells) {
    const Eigen::Vector2d d = mm(p) - a.centre;
    cov += d * d.transpose();
  }
  cov /= static_cast<double>(cells.size());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);
  a.dir = eig.eigenvectors().col(1);
  if (a.dir.x() < 0.0) a.dir = -a.dir;
  a.across_variance_mm2 = std::max(0.0, eig.eigenvalues()(0));
  for (const cv::Point& p : cells) {
    const double t = (mm(p) - a.centre).dot(a.dir);
    a.lo = std::min(a.lo, t);
    a.hi = std::max(a.hi, t);
  }
  return a;
}

int FindRoot(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

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
      Bound(comp);
      out.push_back(std::move(comp));
    }
  }
  return out;
}

std::vector<MapComponent> JoinThroughHoles(const std::vector<MapComponent>& regions,
                                           const cv::Mat1f& values, int max_rows, int max_cols) {
  const int rows = values.rows, cols = values.cols;
  cv::Mat1b missing = cv::Mat1b::zeros(rows, cols);
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) missing(r, c) = std::isfinite(values(r, c)) ? 0 : 2;
  }
  std::vector<MapComponent> holes = HysteresisComponents(missing);
  cv::Mat1i hole_at(rows, cols, -1);
  for (int h = 0; h < static_cast<int>(holes.size()); ++h) {
    const MapComponent& c = holes[h];
    if (c.row_min == 0 || c.row_max == rows - 1 || c.row_max - c.row_min + 1 > max_rows ||
        c.col_max - c.col_min + 1 > max_cols)
      continue;
    for (const cv::Point& p : c.cells) hole_at(p.y, ((p.x % cols) + cols) % cols) = h;
  }
  // Union-find over regions and holes: region i is node i, hole h node regions.size() + h.
  const int n = static_cast<int>(regions.size());
  std::vector<int> parent(n + holes.size());
  std::iota(parent.begin(), parent.end(), 0);
  std::vector<std::set<int>> touched(n);
  for (int i = 0; i < n; ++i) {
    for (const cv::Point& p : regions[i].cells) {
      for (int dr = -1; dr <= 1; ++dr) {
        for (int dc = -1; dc <= 1; ++dc) {
          const int r = p.y + dr;
          if (r < 0 || r >= rows) continue;
          const int h = hole_at(r, ((p.x + dc) % cols + cols) % cols);
          if (h >= 0 && touched[i].insert(h).second)
            parent[FindRoot(parent, n + h)] = FindRoot(parent, i);
        }
      }
    }
  }
  std::vector<MapComponent> out;
  std::vector<int> slot(parent.size(), -1);
  for (int i = 0; i < n; ++i) {
    const int root = FindRoot(parent, i);
    if (slot[root] < 0) {
      slot[root] = static_cast<int>(out.size());
      out.emplace_back();
    }
    MapComponent& joined = out[slot[root]];
    joined.cells.insert(joined.cells.end(), regions[i].cells.begin(), regions[i].cells.end());
  }
  std::vector<bool> taken(holes.size(), false);
  for (int i = 0; i < n; ++i) {
    MapComponent& joined = out[slot[FindRoot(parent, i)]];
    const double centre = 0.5 * (regions[i].col_min + regions[i].col_max);
    for (const int h : touched[i]) {
      if (taken[h]) continue;
      taken[h] = true;
      const MapComponent& hole = holes[h];
      const int shift = static_cast<int>(
          std::lround((centre - 0.5 * (hole.col_min + hole.col_max)) / cols) * cols);
      for (const cv::Point& p : hole.cells) joined.cells.emplace_back(p.x + shift, p.y);
    }
  }
  for (MapComponent& c : out) Bound(c);
  return out;
}

}  // namespace sewer3d
