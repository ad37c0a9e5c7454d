#include "sewer3d/decode/lattice.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <queue>
#include <unordered_map>

#include "sewer3d/core/check.hpp"

namespace sewer3d {
namespace {

/// Uniform grid of spot indices for radius queries.
class SpotGrid {
 public:
  SpotGrid(const std::vector<Spot>& spots, double cell) : spots_(spots), cell_(cell) {
    for (size_t i = 0; i < spots.size(); ++i) cells_[Key(spots[i].centre_px)].push_back(static_cast<int>(i));
  }
  template <class F>
  void ForEachNear(const Eigen::Vector2d& p, double radius, F&& f) const {
    const int r = static_cast<int>(std::ceil(radius / cell_));
    const auto [cx, cy] = Cell(p);
    for (int dy = -r; dy <= r; ++dy) {
      for (int dx = -r; dx <= r; ++dx) {
        const auto it = cells_.find(Pack(cx + dx, cy + dy));
        if (it == cells_.end()) continue;
        for (int j : it->second) {
          if ((spots_[j].centre_px - p).squaredNorm() <= radius * radius) f(j);
        }
      }
    }
  }

 private:
  std::pair<int, int> Cell(const Eigen::Vector2d& p) const {
    return {static_cast<int>(std::floor(p.x() / cell_)), static_cast<int>(std::floor(p.y() / cell_))};
  }
  static long long Pack(int x, int y) { return (static_cast<long long>(x) << 32) ^ static_cast<unsigned>(y); }
  long long Key(const Eigen::Vector2d& p) const {
    const auto [x, y] = Cell(p);
    return Pack(x, y);
  }
  const std::vector<Spot>& spots_;
  double cell_;
  std::unordered_map<long long, std::vector<int>> cells_;
};

// Refines the steps of one spot from its neighbours: assign integer offsets with the current
// steps, then least squares for both steps; twice.
LatticeSteps Refine(const Eigen::Vector2d& p, const std::vector<Eigen::Vector2d>& neighbours,
                    LatticeSteps steps, double max_residual) {
  for (int iteration = 0; iteration < 2; ++iteration) {
    Eigen::Matrix2d basis;
    basis << steps.row_step, steps.column_step;
    const Eigen::Matrix2d inverse = basis.inverse();
    Eigen::Matrix2d normal = Eigen::Matrix2d::Zero(), rhs = Eigen::Matrix2d::Zero();
    int used = 0;
    for (const auto& q : neighbours) {
      const Eigen::Vector2d d = q - p;
      const Eigen::Vector2d ij = (inverse * d).array().round();
      if (ij.isZero() || ij.cwiseAbs().maxCoeff() > 2) continue;  // nearest ring only
      if ((inverse * d - ij).norm() > max_residual) continue;
      normal += ij * ij.transpose();
      rhs += ij * d.transpose();
      ++used;
    }
    if (used < 2 || std::abs(normal.determinant()) < 1e-9) break;
    const Eigen::Matrix2d solution = normal.ldlt().solve(rhs);  // rows: row_step, column_step
    steps.row_step = solution.row(0).transpose();
    steps.column_step = solution.row(1).transpose();
  }
  return steps;
}

}  // namespace

void LatticeOptions::Check() const {
  SEWER3D_CHECK(max_neighbour_px > 0.0, "max_neighbour_px");
  SEWER3D_CHECK(max_residual > 0.0 && max_residual < 0.5, "max_residual " << max_residual);
}

LatticeLabels LabelLatticeWithSteps(const std::vector<Spot>& spots,
                                    const std::vector<LatticeSteps>& predicted,
                                    const LatticeOptions& options) {
  options.Check();
  SEWER3D_CHECK(predicted.size() == spots.size());
  const int n = static_cast<int>(spots.size());
  LatticeLabels labels;
  labels.group.assign(n, -1);
  labels.node.assign(n, Eigen::Vector2i::Zero());
  labels.steps.resize(n);
  const SpotGrid grid(spots, options.max_neighbour_px);
  std::vector<std::vector<int>> neighbours(n);
  for (int i = 0; i < n; ++i) {
    grid.ForEachNear(spots[i].centre_px, options.max_neighbour_px, [&](int j) {
      if (j != i) neighbours[i].push_back(j);
    });
  }
  std::vector<Eigen::Vector2d> positions;
  // Steps change smoothly over the surface: a spot reached from a labelled neighbour starts
  // its refinement from that neighbour's steps, which follow oblique walls far better than
  // the module's fronto-parallel prediction.
  auto refine = [&](int i, const LatticeSteps& start) {
    positions.clear();
    for (int j : neighbours[i]) positions.push_back(spots[j].centre_px);
    labels.steps[i] = Refine(spots[i].centre_px, positions, start, options.max_residual);
  };
  // An edge i -> j predicted with i's steps: the integer offset and how far from it.
  struct Edge {
    double residual;
    int from, to;
    Eigen::Vector2i offset;
    bool operator>(const Edge& other) const { return residual > other.residual; }
  };
  auto edges_of = [&](int i, auto&& emit) {
    Eigen::Matrix2d basis;
    basis << labels.steps[i].row_step, labels.steps[i].column_step;
    const Eigen::Matrix2d inverse = basis.inverse();
    for (int j : neighbours[i]) {
      const Eigen::Vector2d ij_real = inverse * (spots[j].centre_px - spots[i].centre_px);
      const Eigen::Vector2d ij = ij_real.array().round();
      const double residual = (ij_real - ij).norm();
      if (residual > options.max_residual) continue;
      // Far edges amplify any error of the local affine model (curved surfaces, depth
      // changes): beyond three steps a 17 % scale error already picks the wrong node.
      if (ij.cwiseAbs().maxCoeff() > options.max_edge_steps) continue;
      emit(Edge{residual, i, j, Eigen::Vector2i(int(ij.x()), int(ij.y()))});
    }
  };
  // Best-first growth (Prim's order): the most reliable edges label first, so a bad edge can
  // only label a spot no good edge reaches, and seams between propagation fronts fall on
  // the poorest edges.
  std::priority_queue<Edge, std::vector<Edge>, std::greater<Edge>> frontier;
  for (int seed = 0; seed < n; ++seed) {
    if (labels.group[seed] >= 0) continue;
    const int group = labels.groups++;
    labels.group[seed] = group;
    refine(seed, predicted[seed]);
    edges_of(seed, [&](const Edge& e) { frontier.push(e); });
    while (!frontier.empty()) {
      const Edge e = frontier.top();
      frontier.pop();
      if (labels.group[e.to] >= 0) continue;
      labels.group[e.to] = group;
      labels.node[e.to] = labels.node[e.from] + e.offset;
      refine(e.to, labels.steps[e.from]);
      edges_of(e.to, [&](const Edge& next) {
        if (labels.group[next.to] < 0) frontier.push(next);
      });
    }
  }
  // A spot whose label most of its good edges contradict sits on a seam: unlabel it rather
  // than let it corrupt the windows around it.
  std::vector<int> contradicted;
  for (int i = 0; i < n; ++i) {
    int agree = 0, disagree = 0;
    edges_of(i, [&](const Edge& e) {
      if (labels.group[e.to] != labels.group[i]) return;
      (labels.node[e.to] == labels.node[i] + e.offset ? agree : disagree) += 1;
    });
    labels.conflicts += disagree;
    if (disagree > agree) contradicted.push_back(i);
  }
  for (int i : contradicted) labels.group[i] = -1;
  return labels;
}

}  // namespace sewer3d
