#pragma once
// The start of the step being tried, to go back to when it fails. Its displacements are the
// newest converged step's, which that step's record holds until a later step converges (Recorder):
// only λ, the rotations and the contacts with their references are copied (a vector of the
// model's size less at 10⁵ elements and up). Before the first step converges, the displacements
// are copied too.

#include <Eigen/Core>
#include <vector>

#include "tsmframe/solver/state.hpp"

namespace tsm::solver {

class StepStart {
 public:
  /// `recorded`: the newest converged step's displacements as its record holds them (null: none).
  void take(const State& state, const Eigen::VectorXd* recorded) {
    recorded_ = recorded;
    if (recorded) own_.displacements.resize(0);
    else own_.displacements = state.displacements;
    own_.load_factor = state.load_factor;
    own_.chord_rotations = state.chord_rotations;
    own_.contacts = state.contacts;
    own_.contact_references = state.contact_references;
  }
  /// Valid until a step converges (the record may then give up its displacements).
  void restore(State& state) const {
    state.displacements = displacements();
    state.load_factor = own_.load_factor;
    state.chord_rotations = own_.chord_rotations;
    state.contacts = own_.contacts;
    state.contact_references = own_.contact_references;
  }
  double load_factor() const { return own_.load_factor; }
  /// Valid as restore().
  const Eigen::VectorXd& displacements() const { return recorded_ ? *recorded_ : own_.displacements; }
  const std::vector<contact::ContactState>& contacts() const { return own_.contacts; }
  /// The step converged: its start is not needed any more (its own copy goes before the step is
  /// recorded, so that the two never coexist).
  void release() { own_.displacements.resize(0); }

 private:
  State own_;
  const Eigen::VectorXd* recorded_ = nullptr;
};

}  // namespace tsm::solver
