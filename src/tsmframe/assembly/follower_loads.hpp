#pragma once
// Follower loads: a member's pressure ("load": {"pressure": p}), normal to its current element
// chords. On an element of current chord d = x_j − x_i the force is −p l n (n the left normal,
// l n = R d with R the quarter turn [0 −1; 1 0]), lumped half to each end: P_i = P_j = −(p/2) R d.
// So ∂P/∂x_j = −(p/2) R and ∂P/∂x_i = +(p/2) R at both ends, and the tangent gains −λ ∂P/∂D:
// K_ij = λ (p/2) R and K_ji = K_ijᵀ, a symmetric coupling, whatever the geometry; K_ii = −λ (p/2)
// R and K_jj = +λ (p/2) R are skew and cancel wherever two elements of equal pressure meet (a
// closed ring: the load is conservative). Where they do not (a loaded stretch ending at a free
// node, a change of pressure) a node keeps c R, c = λ Σ ±p/2: two rank-one terms for the linear
// solver. Without them Newton crawled where the structure is soft (a cantilever rolled 3.3 rad
// by pressure: 1,729 iterations in 38 steps; with them ≤ 15 a step in 5).
// An earlier stage's follower loads are held at their final level (MemberExtras::dead_pressure,
// FollowerForce::dead): they enter the dead load, and the tangent with the factor 1 for λ.

#include <Eigen/Core>
#include <vector>

#include "tsmframe/assembly/dof_map.hpp"
#include "tsmframe/linalg/rank_one.hpp"
#include "tsmframe/model/model.hpp"
#include "tsmframe/model/nodal_frames.hpp"

namespace tsm::assembly {

class FollowerLoads {
 public:
  /// `frames`: the skew rollers' (the skew terms' rows are turned into them).
  FollowerLoads(const Model& model, const DofMap& dofs, const NodalFrames& frames);
  bool empty() const { return loads_.empty() && model_.follower_forces.empty(); }

  /// The reference load at `displacements` (all dofs): the model's, plus the follower loads on
  /// the current geometry (pressure on the current chords, point loads turned with their nodes),
  /// at λ = 1. Dead follower loads are left out (dead_load).
  void reference_load(const Eigen::VectorXd& displacements, Eigen::VectorXd& out) const;
  /// Whether an earlier stage left follower loads (then the dead load depends on the geometry).
  bool has_dead() const { return has_dead_; }
  /// The dead load at `displacements`: the model's dead_load plus the dead follower loads.
  void dead_load(const Eigen::VectorXd& displacements, Eigen::VectorXd& out) const;

  /// add(node_i, node_j, K_ij) for each load's symmetric coupling K_ij = λ (p/2) R (on the
  /// translations of a 3×3 block), in the model's element order; with `only`, just the loads with
  /// a node marked there.
  template <class Add>
  void couplings(double load_factor, const std::vector<char>* only, Add&& add) const {
    for (const Load& f : loads_) {
      if (only && !(*only)[f.start] && !(*only)[f.end]) continue;
      Eigen::Matrix3d coupling = Eigen::Matrix3d::Zero();
      const double p = level(load_factor, f.pressure, f.dead_pressure);
      coupling(0, 1) = -0.5 * p;
      coupling(1, 0) = 0.5 * p;
      add(f.start, f.end, coupling);
    }
  }

  /// The skew rest c R at the nodes where loaded stretches end, as rank-one terms over the free
  /// equations (K_uv −= c, K_vu += c), and each follower point load's −λ Q R(θ) F on its node's
  /// free rotation, into `out` (cleared first).
  void skew_terms(double load_factor, const Eigen::VectorXd& displacements, std::vector<linalg::RankOne>& out) const;

 private:
  struct Load {
    int start = 0, end = 0;  ///< node indices
    double pressure = 0.0, dead_pressure = 0.0;
  };
  /// A load's level at λ: λ times its live part plus its dead part.
  static double level(double load_factor, double live, double dead) {
    return dead == 0.0 ? load_factor * live : load_factor * live + dead;
  }
  /// Adds the live (dead = false) or the dead follower loads at `displacements` to `out`.
  void add_loads(const Eigen::VectorXd& displacements, bool dead, Eigen::VectorXd& out) const;

  const Model& model_;
  const DofMap& dofs_;
  const NodalFrames& frames_;
  std::vector<Load> loads_;                    ///< per loaded element, in the model's order
  struct Skew {
    int node = 0;
    double live = 0.0, dead = 0.0;  ///< Σ ±p/2 of the live and the dead pressures
  };
  std::vector<Skew> skew_;  ///< where a sum is not 0
  bool has_dead_ = false;
};

}  // namespace tsm::assembly
