#pragma once
/// \file
/// Pose-graph optimisation with Ceres (Levenberg–Marquardt, sparse Cholesky), with an optional
/// global initialisation (chordal relaxation of the rotations, then linear translations;
/// Carlone et al., ICRA 2015) for graphs where LM from odometry falls into local minima.

#include <string>

#include "sewer3d/posegraph/pose_graph.hpp"

namespace sewer3d {

enum class PoseGraphInit {
  kGiven,    ///< start from the graph's own poses (odometry)
  kChordal,  ///< start from the chordal initialisation
  kAuto,     ///< chordal when it lowers the cost of the given poses, else given
};

struct PoseGraphOptions {
  PoseGraphInit init = PoseGraphInit::kAuto;
  int max_iterations = 100;
  int num_threads = 1;
  /// Huber scale applied to every edge that has none of its own (<= 0: none).
  double huber_delta = 0.0;
  double function_tolerance = 1e-8;
  double gradient_tolerance = 1e-10;
  double parameter_tolerance = 1e-10;
  /// After LM, run the Riemannian staircase (certificate.hpp) from the result: it gives a lower
  /// bound on the global optimum, and where its rounded solution refines to a lower cost, that
  /// solution is taken. Not with robust losses.
  bool certify = false;
  void Check() const;
};

struct PoseGraphReport {
  std::string init_used;      ///< "given" or "chordal"
  double given_cost = 0.0;    ///< ½ Σ rᵀΩr at the graph's own poses
  double initial_cost = 0.0;  ///< at the start of LM (after initialisation)
  double final_cost = 0.0;    ///< ½ Σ rᵀΩr at the result (without robust loss)
  int iterations = 0;
  double init_seconds = 0.0;
  double solve_seconds = 0.0;
  std::string termination;  ///< Ceres' termination type and message
  bool usable = false;      ///< converged (or hit the budget while decreasing) with finite poses
  int nodes = 0, edges = 0;
  /// Nodes with no chain of edges to a fixed node (or to the first when none is fixed): nothing
  /// determines their poses, which stay as given. A caller decides whether that is acceptable
  /// (the registration keeps odometry poses so; `sewer3d posegraph` refuses).
  int unanchored_nodes = 0;

  /// With PoseGraphOptions::certify:
  bool certificate_applicable = false;
  std::string certificate_reason;     ///< why not applicable, or why not converged
  double lower_bound = 0.0;           ///< no poses of this graph cost less
  int relaxation_rank = 0;            ///< rank at which the staircase stopped
  bool relaxation_solved = false;     ///< the semidefinite relaxation was solved (S ⪰ 0)
  int dominated_edges = 0;            ///< edges with lowered information (certificate.hpp)
  bool dominated_relaxation = false;  ///< the bound comes from the dominated-information relaxation
  bool certificate_improved = false;  ///< the staircase's rounded solution beat LM's and was taken
  double certificate_seconds = 0.0;
  /// final_cost is within this fraction of the global optimum (final − bound) / final.
  double RelativeGap() const {
    return final_cost > 0.0 ? (final_cost - lower_bound) / final_cost : 0.0;
  }
};

/// Chordal initialisation: rotations from the linear relaxation Σ w‖R_b − R_a R̂_ab‖²_F
/// projected onto SO(3), then positions from the linear least squares
/// Σ (p_b − p_a − R_a p̂_ab)ᵀ Ω_w (p_b − p_a − R_a p̂_ab); fixed nodes (or the first) anchor
/// the gauge. Returns false (graph unchanged) if the linear systems are singular, e.g. the
/// graph is disconnected.
bool ChordalInitialisation(PoseGraph& graph);

/// Optimises the graph's poses in place and reports.
PoseGraphReport OptimisePoseGraph(PoseGraph& graph, const PoseGraphOptions& options);

}  // namespace sewer3d
