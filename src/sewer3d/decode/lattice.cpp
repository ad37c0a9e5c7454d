#include "sewer3d/decode/lattice.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <queue>

#include "sewer3d/core/check.hpp"
#include "sewer3d/core/neighbours.hpp"

namespace sewer3d {
namespace {

// Nearest integer, without the libm call Eigen's round() makes.
inline Eigen::Vector2d Nearest(const Eigen::Vector2d& x) {
  return {std::floor(x.x() + 0.5), std::floor(x.y() + 0.5)};
}

// The pattern lights no two adjacent elements, so every other column (or row) alone is a
// lattice too, and a fit can drift to it: its step twice the true one, the spots of the other
// columns then sitting half a step off, where a true lattice has none. Where the neighbours
// half a step off are as common as those on the lattice, the step is halved.
void HalveDoubledSteps(const std::vector<Spot>& spots, const Eigen::Vector2d& p,
                       std::pair<const int*, const int*> neighbours, int rings, double max_residual,
                       Eigen::Matrix2d& solution) {
  Eigen::Matrix2d basis;
  basis << solution.row(0).transpose(), solution.row(1).transpose();
  if (std::abs(basis.determinant()) < 1e-9) return;
  const Eigen::Matrix2d inverse = basis.inverse();
  int on = 0;
  Eigen::Vector2i half = Eigen::Vector2i::Zero();  // on in one index, half a step off in the other
  for (const int* it = neighbours.first; it != neighbours.second; ++it) {
    const Eigen::Vector2d q = inverse * (spots[*it].centre_px - p);
    if (q.cwiseAbs().maxCoeff() > rings + 0.5) continue;
    const Eigen::Vector2d f = (q - Nearest(q)).cwiseAbs();  // ≤ 0.5
    const bool row_on = f.x() < max_residual, col_on = f.y() < max_residual;
    // Half a step off: within half the residual limit of it.
    const bool row_half = f.x() > 0.5 - 0.5 * max_residual;
    const bool col_half = f.y() > 0.5 - 0.5 * max_residual;
    if (row_on && col_on) ++on;
    if (row_half && col_on) ++half.x();
    if (row_on && col_half) ++half.y();
  }
  // The doubled lattice leaves about as many spots half a step off as on it; random offsets
  // (a poor fit) a quarter as many.
  for (int k = 0; k < 2; ++k)
    if (half[k] >= 2 && 2 * half[k] >= on) solution.row(k) *= 0.5;
}

// Refines the steps of one spot from its neighbours: assign integer offsets with the current
// steps, then least squares for both steps, over refine_ring_steps rings; from a poor start
// over the two nearest first (steps a tilt's 15 % off round a neighbour three pitches out to
// the wrong offset, two pitches out they do not).
LatticeSteps Refine(const std::vector<Spot>& spots, int spot,
                    std::pair<const int*, const int*> neighbours, LatticeSteps steps,
                    const LatticeSteps& predicted, bool from_neighbour,
                    const LatticeOptions& options) {
  const Eigen::Vector2d& p = spots[spot].centre_px;
  const int near_rings = std::min(2, options.refine_ring_steps);
  constexpr double kGoodStartShare = 0.7;
  for (int iteration = 0; iteration < 3; ++iteration) {
    Eigen::Matrix2d basis;
    basis << steps.row_step, steps.column_step;
    const Eigen::Matrix2d inverse = basis.inverse();
    // Normal equations over all rings and over the near ones; the share of the neighbours out
    // to all rings that the current steps place on the lattice.
    Eigen::Matrix2d normal = Eigen::Matrix2d::Zero(), rhs = Eigen::Matrix2d::Zero();
    Eigen::Matrix2d near_normal = Eigen::Matrix2d::Zero(), near_rhs = Eigen::Matrix2d::Zero();
    int used = 0, near_used = 0, on = 0, within = 0, odd_used = 0, near_odd_used = 0;
    for (const int* it = neighbours.first; it != neighbours.second; ++it) {
      const Eigen::Vector2d d = spots[*it].centre_px - p;
      const Eigen::Vector2d q = inverse * d;
      const Eigen::Vector2d ij = Nearest(q);
      const double ring = ij.cwiseAbs().maxCoeff();
      const bool fits = (q - ij).norm() <= options.max_residual;
      if (q.cwiseAbs().maxCoeff() <= options.refine_ring_steps + 0.5) {
        ++within;
        on += fits ? 1 : 0;
      }
      if (ij.isZero() || ring > options.refine_ring_steps || !fits) continue;
      const bool odd_row = static_cast<int>(ij.x()) % 2 != 0;
      normal += ij * ij.transpose();
      rhs += ij * d.transpose();
      ++used;
      odd_used += odd_row ? 1 : 0;
      if (ring > near_rings) continue;
      near_normal += ij * ij.transpose();
      near_rhs += ij * d.transpose();
      ++near_used;
      near_odd_used += odd_row ? 1 : 0;
    }
    // A start that fits most neighbours out to all rings (a neighbour's steps, mostly) is
    // refined over all of them at once; a poor one (the module's prediction on a tilted
    // board) over the near rings first.
    int rings = options.refine_ring_steps;
    if (iteration == 0 && on < kGoodStartShare * within) {
      rings = near_rings;
      normal = near_normal;
      rhs = near_rhs;
      used = near_used;
      odd_used = near_odd_used;
    }
    if (used < 2 || std::abs(normal.determinant()) < 1e-9) break;
    Eigen::Matrix2d solution = normal.ldlt().solve(rhs);  // rows: row_step, column_step
    // No neighbour on an odd row: the pattern leaves every other row dark over up to 15
    // columns (rows 0, 2 and 4 of the default array between columns 145 and 159), and there a
    // row step sheared by half a column fits as well as the true one, so the fit cannot tell
    // how far the row step leans along the columns. Started from a labelled neighbour's steps
    // (which bring the lean from where the rows are lit), the lean is kept. Refitted, it
    // drifted with the spots' scatter from spot to spot across the dark rows until a third of a
    // column was passed, and the labels slipped a column every other row: a Ø200 wall's lower
    // corners decoded elements three to five columns off (points 1.5–2.8 mm deep, `paper` with
    // 0.65 px of placement). A seed's start is the module's prediction, whose lean is not worth
    // keeping (a tilted board's is far off).
    if (odd_used == 0 && from_neighbour) {
      const Eigen::Vector2d along = solution.row(1).transpose().normalized();
      const Eigen::Vector2d fitted = solution.row(0).transpose();
      solution.row(0) = (fitted - (fitted - steps.row_step).dot(along) * along).transpose();
    }
    HalveDoubledSteps(spots, p, neighbours, rings, options.max_residual, solution);
    // The pattern lights no two adjacent elements, so every other column (or row) alone is
    // a lattice too: a fit whose step drifted to twice its length (or half) still matches
    // most neighbours, and the labels grown from it are scaled. The module predicts each
    // step's length to within about 20 % over the working range (oblique walls included).
    const auto scaled = [&](const Eigen::Vector2d& step, const Eigen::Vector2d& predicted) {
      const double ratio = step.norm() / predicted.norm();
      return ratio > options.max_step_scale || ratio < 1.0 / options.max_step_scale;
    };
    if (scaled(solution.row(0).transpose(), predicted.row_step) ||
        scaled(solution.row(1).transpose(), predicted.column_step))
      break;
    const double change = (solution.row(0).transpose() - steps.row_step).norm() +
                          (solution.row(1).transpose() - steps.column_step).norm();
    steps.row_step = solution.row(0).transpose();
    steps.column_step = solution.row(1).transpose();
    // Started from a neighbour's steps, one pass rarely moves them enough to change which
    // integer offset a neighbour gets; another pass is needed only after a large change, or
    // to take the outer rings in.
    const bool all_rings = rings == options.refine_ring_steps;
    if (all_rings && change < 0.02 * (steps.row_step.norm() + steps.column_step.norm())) break;
  }
  return steps;
}

// How many neighbours out to `rings` steps `steps` place on the lattice (within max_residual
// of a node), of how many.
struct Support {
  int on = 0, within = 0;
};
Support LatticeSupport(const std::vector<Spot>& spots, int spot,
                       std::pair<const int*, const int*> neighbours, const LatticeSteps& steps,
                       const LatticeOptions& options) {
  Eigen::Matrix2d basis;
  basis << steps.row_step, steps.column_step;
  Support support;
  if (std::abs(basis.determinant()) < 1e-9) return support;
  const Eigen::Matrix2d inverse = basis.inverse();
  for (const int* it = neighbours.first; it != neighbours.second; ++it) {
    const Eigen::Vector2d q = inverse * (spots[*it].centre_px - spots[spot].centre_px);
    if (q.cwiseAbs().maxCoeff() > options.refine_ring_steps + 0.5) continue;
    ++support.within;
    support.on += (q - Nearest(q)).norm() <= options.max_residual ? 1 : 0;
  }
  return support;
}

// A group's spots start their refinement from a labelled neighbour's steps, so the seed's
// steps carry over the whole group. The pattern lights about one element in six, so a lattice
// whose row step is sheared by half a column (b ± a/2) still fits every other row: a seed
// with few neighbours (the image border, a dark patch) can settle there, and its group
// inherits it (a dark clay frame lost half its decoded spots). A seed is taken only where its
// steps place nearly all of at least `kSeedMinOn` neighbours on the lattice (the three rings
// hold about eight spots); a spot where they do not waits until no such seed is left.
constexpr int kSeedMinOn = 6;
constexpr double kSeedMinShare = 0.9;
bool GoodSeed(const Support& s) { return s.on >= kSeedMinOn && s.on >= kSeedMinShare * s.within; }
// Nor where its steps lean off the module's prediction by more than this share of a step: a
// spot whose rings are one-sided (beside a shadow band, near the border) fits a lattice that
// leans by a fifth of a column and still holds its neighbours. A shadow band that cut the
// wall off from the first seed let such a seed label 10 155 spots, of which 2 829 decoded
// (docs/decoder.md). Such a spot is not refused: it waits, and seeds in order of support once
// no seed near the prediction is left (an oblique wall's steps may lie 0.8–1.2 times it).
constexpr double kSeedMaxLean = 0.15;
constexpr int kLeanSample = 256;  // spots sampled to judge whether the prediction holds
// Fewer well-supported spots than this in the sample say nothing about the prediction: a
// close tilted board (few spots anywhere fit the prediction's lattice well) gave 0–4 of 256,
// and four near the prediction once turned the check on and its seeds grew the wrong
// lattices (12 % of the windows decoded; 0.65 px of placement, docs/decoder.md). Walls give
// 9–56.
constexpr int kLeanMinGood = 8;
bool NearPrediction(const LatticeSteps& steps, const LatticeSteps& predicted) {
  return (steps.row_step - predicted.row_step).norm() < kSeedMaxLean * predicted.row_step.norm() &&
         (steps.column_step - predicted.column_step).norm() <
             kSeedMaxLean * predicted.column_step.norm();
}

}  // namespace

void LatticeOptions::Check() const {
  ValidatePositive("max_neighbour_px", max_neighbour_px);
  SEWER3D_VALIDATE(max_residual > 0.0 && max_residual < 0.5, "max_residual",
                   "must be > 0 and < 0.5, got " << max_residual);
  SEWER3D_VALIDATE(refine_ring_steps >= 1 && refine_ring_steps <= 6, "refine_ring_steps",
                   "must be 1..6, got " << refine_ring_steps);
  SEWER3D_VALIDATE(max_step_scale > 1.0, "max_step_scale",
                   "must be above 1, got " << max_step_scale);
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
  const NeighbourLists neighbours =
      RadiusNeighbours(n, options.max_neighbour_px,
                       [&](int i) -> const Eigen::Vector2d& { return spots[i].centre_px; });
  // Steps change smoothly over the surface: a spot reached from a labelled neighbour starts
  // its refinement from that neighbour's steps, which follow oblique walls far better than
  // the module's fronto-parallel prediction.
  auto refine = [&](int i, const LatticeSteps& start, bool from_neighbour) {
    labels.steps[i] =
        Refine(spots, i, neighbours.Of(i), start, predicted[i], from_neighbour, options);
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
    const auto [first, last] = neighbours.Of(i);
    for (const int* it = first; it != last; ++it) {
      const int j = *it;
      const Eigen::Vector2d ij_real = inverse * (spots[j].centre_px - spots[i].centre_px);
      const Eigen::Vector2d ij = Nearest(ij_real);
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
  // Only an edge better than the best one already queued for its target can matter (the
  // better one labels the target first): the heap stays small.
  std::vector<double> best_queued(n, 1e300);
  // Each spot's good edges, found once when it is labelled (its steps are final then) and
  // kept for the seam check below.
  std::vector<std::pair<int, Eigen::Vector2i>> good_edges;
  good_edges.reserve(static_cast<size_t>(n) * 8);
  std::vector<int> edge_begin(n, 0), edge_end(n, 0);
  auto label_edges = [&](int i) {
    edge_begin[i] = static_cast<int>(good_edges.size());
    edges_of(i, [&](const Edge& e) {
      good_edges.emplace_back(e.to, e.offset);
      if (labels.group[e.to] < 0 && e.residual < best_queued[e.to]) {
        best_queued[e.to] = e.residual;
        frontier.push(e);
      }
    });
    edge_end[i] = static_cast<int>(good_edges.size());
  };
  auto grow = [&](int seed) {
    const int group = labels.groups++;
    labels.group[seed] = group;
    label_edges(seed);
    while (!frontier.empty()) {
      const Edge e = frontier.top();
      frontier.pop();
      if (labels.group[e.to] >= 0) continue;
      labels.group[e.to] = group;
      labels.node[e.to] = labels.node[e.from] + e.offset;
      refine(e.to, labels.steps[e.from], /*from_neighbour=*/true);
      label_edges(e.to);
    }
  };
  // The lean check trusts the module's fronto-parallel prediction. Where most well-supported
  // spots lie off it (a calibration board tilted by 35° close to the module), the few fits
  // near it are the wrong ones, and seeding only from them lost whole boards: it applies
  // where most of a sample of well-supported spots agree with the prediction.
  int sampled_good = 0, sampled_near = 0;
  for (int i = 0; i < n; i += std::max(1, n / kLeanSample)) {
    const LatticeSteps steps =
        Refine(spots, i, neighbours.Of(i), predicted[i], predicted[i], false, options);
    if (!GoodSeed(LatticeSupport(spots, i, neighbours.Of(i), steps, options))) continue;
    ++sampled_good;
    sampled_near += NearPrediction(steps, predicted[i]) ? 1 : 0;
  }
  const bool check_lean = sampled_good >= kLeanMinGood && 2 * sampled_near >= sampled_good;
  // Well-supported seeds first (GoodSeed), in index order; then the rest, best supported first.
  std::vector<std::pair<int, int>> waiting;  // (−neighbours on the lattice, spot)
  for (int seed = 0; seed < n; ++seed) {
    if (labels.group[seed] >= 0) continue;
    refine(seed, predicted[seed], /*from_neighbour=*/false);
    const Support support =
        LatticeSupport(spots, seed, neighbours.Of(seed), labels.steps[seed], options);
    if (GoodSeed(support) && (!check_lean || NearPrediction(labels.steps[seed], predicted[seed])))
      grow(seed);
    else
      waiting.emplace_back(-support.on, seed);
  }
  // A waiting spot still unlabelled keeps the steps refined from the prediction above.
  std::sort(waiting.begin(), waiting.end());
  for (const auto& [minus_on, seed] : waiting)
    if (labels.group[seed] < 0) grow(seed);
  // A spot whose label most of its good edges contradict sits on a seam: unlabel it rather
  // than let it corrupt the windows around it.
  std::vector<int> contradicted;
  for (int i = 0; i < n; ++i) {
    int agree = 0, disagree = 0;
    for (int k = edge_begin[i]; k < edge_end[i]; ++k) {
      const auto& [to, offset] = good_edges[k];
      if (labels.group[to] != labels.group[i]) continue;
      (labels.node[to] == labels.node[i] + offset ? agree : disagree) += 1;
    }
    labels.conflicts += disagree;
    if (disagree > agree) contradicted.push_back(i);
  }
  for (int i : contradicted) labels.group[i] = -1;
  return labels;
}

}  // namespace sewer3d
