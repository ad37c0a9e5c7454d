#pragma once
/// \file
/// Recovery of the projected spot lattice in the camera image (paper §decode): every spot
/// gets integer lattice coordinates (row, col) in projector element units, consistent within
/// its connected group. Locally the lattice is affine: a neighbour at displacement d sits at
/// (i, j) with d ≈ i·b + j·a, a and b the camera images of one projector column and row step.
/// They are refined per spot from its neighbours, starting from the module's prediction, so
/// lens distortion, perspective and depth changes bend the lattice without breaking it.

#include <Eigen/Core>
#include <vector>

#include "sewer3d/decode/spots.hpp"

namespace sewer3d {

struct LatticeOptions {
  /// Neighbours considered for the local lattice: isolated spots can leave gaps of three
  /// elements, and perspective stretches an 8 px pitch to ~9 px, so 4 steps.
  double max_neighbour_px = 36.0;
  double max_residual = 0.25;  ///< |d − (i b + j a)| limit, in lattice steps
  int max_edge_steps = 3;      ///< longest edge used for labelling, in lattice steps
  /// A spot's own steps are fitted to its neighbours up to this many steps away. The pattern
  /// lights about one element in six, so the nearest two rings hold four spots on average
  /// and a fit from two of them takes their noise into both steps: with a real module's spot
  /// scatter (0.6 px, docs/accuracy.md) the labels broke into small contradicting groups (9 %
  /// of a close plane's spots decoded, 98 % with three rings, which hold eight). From a poor
  /// start (steps that place under 70 % of these neighbours on the lattice) the first pass
  /// takes two rings: from steps a tilt's 15 % off, a third ring's neighbours round to the
  /// wrong offset (a tilted calibration board lost its whole lattice).
  int refine_ring_steps = 3;
  /// A refined step longer than this many times the predicted one, or shorter than its
  /// inverse, is not taken: the fit has found every other column or row (lattice.cpp).
  /// Measured on the accuracy scenes: 0.78–1.17 times the prediction.
  double max_step_scale = 1.6;
  void Check() const;
};

/// Predicted camera-image lattice steps at a pixel: a = +1 projector column, b = +1 row.
struct LatticeSteps {
  Eigen::Vector2d column_step;
  Eigen::Vector2d row_step;
};

struct LatticeLabels {
  std::vector<int> group;             ///< per spot: connected group id, −1 if unlabelled
  std::vector<Eigen::Vector2i> node;  ///< per spot: (row, col) lattice coordinates in its group
  std::vector<LatticeSteps> steps;    ///< per spot: refined local steps
  int groups = 0;
  int conflicts = 0;  ///< good edges whose offset contradicts the labels
};

/// Labels spots by breadth-first propagation over neighbour edges that fit the local lattice.
/// `predict(p)` gives the expected steps at camera pixel p (from the module geometry).
template <class Predict>
LatticeLabels LabelLattice(const std::vector<Spot>& spots, const LatticeOptions& options,
                           Predict&& predict);

/// Non-template core: steps predicted per spot are passed in.
LatticeLabels LabelLatticeWithSteps(const std::vector<Spot>& spots,
                                    const std::vector<LatticeSteps>& predicted,
                                    const LatticeOptions& options);

template <class Predict>
LatticeLabels LabelLattice(const std::vector<Spot>& spots, const LatticeOptions& options,
                           Predict&& predict) {
  std::vector<LatticeSteps> predicted;
  predicted.reserve(spots.size());
  for (const Spot& s : spots) predicted.push_back(predict(s.centre_px));
  return LabelLatticeWithSteps(spots, predicted, options);
}

}  // namespace sewer3d
