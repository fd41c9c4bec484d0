#pragma once
// A one-dof problem for Newton (solver/problem.hpp): a nonlinear spring F(u) = k u + c u³ under
// the load λ·1. With c > 0 it hardens (one equilibrium for every λ); with c < 0 it softens, and
// its load has a maximum λ_max = (2k/3) √(k / (−3c)) at u = √(k / (−3c)) (a limit point).

#include <cmath>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "tsmframe/solver/problem.hpp"

namespace tsm::test {

class ToyProblem final : public solver::Problem {
 public:
  ToyProblem(double k, double c) : k_(k), c_(c) {
    equations_.free_dofs = std::span<const int>(free_dof_);
    equations_.is_moment = {0};
    equations_.size = 1.0;
    equations_.resolvable_move = 1e12;
  }

  double force(double u) const { return k_ * u + c_ * u * u * u; }
  double stiffness(double u) const { return k_ + 3.0 * c_ * u * u; }
  int evaluations() const { return evaluations_; }
  /// How far from the solution Newton said each evaluation was, in order.
  const std::vector<solver::Proximity>& proximities() const { return proximities_; }
  /// The reference load (1 unless set).
  void set_load(double load) { load_[0] = load; }

  const solver::Equations& equations() const override { return equations_; }
  bool has_contacts() const override { return false; }
  double step_fraction(const solver::State&, const Eigen::VectorXd&) override { return 1.0; }
  using solver::Problem::evaluate;
  bool evaluate(solver::State& state, solver::Proximity proximity) override {
    ++evaluations_;
    proximities_.push_back(proximity);
    internal_[0] = force(state.displacements[0]);
    tangent_ = stiffness(state.displacements[0]);
    return false;
  }
  const Eigen::VectorXd& internal_force() const override { return internal_; }
  const Eigen::VectorXd& reference_load() const override { return load_; }
  const Eigen::VectorXd& dead_load() const override { return none_; }
  const Eigen::VectorXd& prescribed_coupling() const override { return none_; }
  assembly::RoundingFloor rounding_floor(const solver::State& state, bool) const override {
    assembly::RoundingFloor floor;  // ε times the terms of F
    const double u = state.displacements[0];
    floor.force = std::numeric_limits<double>::epsilon() * (std::abs(k_ * u) + std::abs(c_ * u * u * u));
    floor.moment = floor.force;
    return floor;
  }
  bool has_optional_terms() const override { return false; }
  solver::Factorisation factorize(const solver::State&, bool, Eigen::VectorXd* rhs, bool) override {
    if (!(tangent_ != 0.0) || !std::isfinite(tangent_)) return {false, -1};
    if (rhs) (*rhs)[0] /= tangent_;
    return {true, tangent_ < 0.0 ? 1 : 0};
  }
  void solve_in_place(Eigen::VectorXd& x) const override { x[0] /= tangent_; }
  void begin_step(const solver::State&) override {}
  std::optional<solver::StepFailure> after_iterate(const solver::State&) const override { return std::nullopt; }
  solver::Settlement at_convergence(solver::State&) override { return {}; }
  std::vector<std::pair<int, int>> accept(solver::State&) override { return {}; }
  void explain(const solver::State&, solver::StepFailure&) override {}
  std::vector<solver::ContactPoint> contact_points(const solver::State&) const override { return {}; }

  /// The unloaded state.
  static solver::State start() { return {Eigen::VectorXd::Zero(1), 0.0, {}, {}}; }

 private:
  double k_, c_;
  int free_dof_[1] = {0};
  solver::Equations equations_;
  Eigen::VectorXd internal_ = Eigen::VectorXd::Zero(1), load_ = Eigen::VectorXd::Ones(1), none_;
  double tangent_ = 0.0;
  int evaluations_ = 0;
  std::vector<solver::Proximity> proximities_;
};

}  // namespace tsm::test
