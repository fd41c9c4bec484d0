#pragma once
// What the solver reports: one record per step (converged, or the failed last attempt) and
// how the run ended.

#include <Eigen/Core>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "tsmframe/contact/contact_state.hpp"
#include "tsmframe/model/mechanism.hpp"
#include "tsmframe/solver/buckling.hpp"
#include "tsmframe/solver/criterion.hpp"
#include "tsmframe/solver/failure.hpp"
#include "tsmframe/solver/state.hpp"
#include "tsmframe/solver/status.hpp"

namespace tsm::solver {

/// A contact node at one point of the path.
struct ContactPoint {
  int element = -1;    ///< element index carrying it, −1 when not in contact
  double alpha = 0.0;  ///< α = l_ic / l
  double force = 0.0;  ///< compression (≥ 0 at convergence)
  double Y = 0.0;      ///< Y of the contact element (chord frame)
  int partner = -1;    ///< at a vertex (a beam node, both elements in contact): the other element
  double partner_Y = 0.0;  ///< … and its Y
  /// The push the contact node gives the beam (at a vertex, both elements'), along the normal
  /// its contact asks for.
  Eigen::Vector2d push = Eigen::Vector2d::Zero();
  /// Friction (μ > 0): stick or slip at the step, the force along the beam's tangent (signed
  /// along the touched element's direction) and the slip since the contact touched.
  contact::FrictionStatus friction = contact::FrictionStatus::none;
  double tangential = 0.0;
  double slip = 0.0;
};

struct StepRecord {
  int step = 0;                        ///< 1-based, numbered through a staged run's stages
  int stage = 0;                       ///< index of its stage (Model::stages; 0 without stages)
  double load_factor = 0.0;            ///< λ at the end of the step (at the start of a failed or cut-back attempt)
  bool converged = false;
  /// An attempt that failed and is tried again smaller (cutback): shown to the observer, with
  /// `message` saying why, and never kept in the results.
  bool cut_back = false;
  int iterations = 0;                  ///< Newton solves, the predictor included
  std::vector<double> residual_norms;  ///< relative ‖R‖ of each iterate, iterate 0 first
  Criterion criterion = Criterion::none;  ///< what ended a converged step (criterion_name: "force", "round-off")
  /// Contacts that let go in the step because their point left a beam's free end: (contact
  /// index, the element whose end it left).
  std::vector<std::pair<int, int>> slid_off;
  int cutbacks = 0;                    ///< failed attempts halved away before this step
  /// The farthest a node moved in the step, ‖Δ(u, v)‖ against the converged step before it
  /// (converged steps): with Δλ, how soft the step was (snap notes under load control).
  double largest_move = 0.0;
  /// Negative eigenvalues of the tangent stiffness at the converged state (its inertia): 0 a
  /// stable equilibrium, n > 0 an unstable one (past a limit or bifurcation point); −1 unknown
  /// (a contact is active, or a follower load is not conservative: the tangent is then not
  /// symmetric; or round-off leaves the count in doubt: RunResult::rounded_steps).
  int negative_eigenvalues = -1;
  /// The supports let a part move here as a rigid body, its loads doing no work along the motion
  /// (RunResult::neutral_steps says how): the tangent is singular, negative_eigenvalues unknown.
  bool neutral = false;
  double increment = 0.0;              ///< Δλ (load and arc-length control) or the controlled dof's increment
  double arc_length = 0.0;             ///< Δs of the step (arc-length control; 0 otherwise)
  std::string message;                 ///< why a failed step (or a cut-back attempt) failed
  Eigen::VectorXd monitored;           ///< (u, v, Θ) of each monitored node (converged steps)
  /// The reaction at each dof a prescribed displacement moves (Model::moved_dofs; converged
  /// steps): the force that drives a displacement-driven model, kept for every step.
  Eigen::VectorXd moved_reactions;
  bool has_state = false;              ///< the arrays below are filled
  Eigen::VectorXd displacements;       ///< all dofs
  Eigen::VectorXd element_forces;      ///< (N, M_i, M_j) per element
  /// The largest axial strain N / EA of an element (signed: > 0 stretched), and that element's
  /// index (−1: not known — a step whose element forces were never computed, see Recorder).
  double axial_strain = 0.0;
  int strained_element = -1;
  Eigen::VectorXd reactions;           ///< all dofs; zero where the dof is free
  /// What a run restarted from this step needs beside its displacements (restart.hpp): where
  /// along its control's path it is (State::path_parameter), the elements' chord rotations
  /// (totals, carried through turns), the contacts (without their references and step memory),
  /// and, in a staged run, the λ each earlier stage ended at and where the dofs its stage
  /// prescribes or controls stood at the stage's start (dof, value).
  double path_parameter = 0.0;
  ArcLengthMemory arc_memory;  ///< under arc-length control (state.hpp)
  std::vector<double> chord_rotations;
  std::vector<contact::ContactState> contact_states;
  std::vector<double> stage_load_factors;
  std::vector<std::pair<int, double>> stage_start;
  std::vector<ContactPoint> contacts;  ///< one per contact of the model (converged steps)
  /// Per iterate (iterate 0 = the step's start), one entry per contact: how α moved.
  std::vector<std::vector<ContactPoint>> contact_iterates;
};

/// A limit point located between the converged steps around it (solver/limit_point): λ's
/// extremum and where it is, as the value of one dof.
struct RefinedLimit {
  int step = 0;               ///< the converged step nearest it
  double load_factor = 0.0;   ///< λ at the extremum
  int dof = 0;                ///< the dof that located it (global), and its value there
  double value = 0.0;
  int evaluations = 0;        ///< equilibria solved to find it
};

/// A converged step where λ is largest or smallest among its neighbours on the path.
struct LimitPoint {
  int step = 0;
  bool maximum = true;
  double load_factor = 0.0;
  std::optional<RefinedLimit> refined;  ///< arc-length control without contacts
  /// A contact point changed elements between the steps around it (passed an element end, touched
  /// or let go): the contact's path kinks there, and the extremum may be the mesh's, not the structure's.
  bool contact_kink = false;
};

/// Where the tangent lost its positive definiteness between two converged steps under load
/// control without a limit point (a bifurcation of the primary path): the load factor found by
/// bisection on the tangent's inertia, within [stable, unstable].
struct CriticalPoint {
  int step = 0;                ///< the first unstable step
  double load_factor = 0.0;    ///< the bracket's middle
  double stable = 0.0, unstable = 0.0;  ///< the bracket: equilibria solved there, stable and not
  bool rounded = false;  ///< the bisection stopped where round-off left the count in doubt
};

/// Where round-off leaves the tangent's inertia unknown (linalg/inertia.hpp): the pivot whose
/// sign is lost — its node (index), the dof it acts most along (0 u, 1 v, 2 θ, in the node's
/// frame) and its size against that node's own diagonal stiffness there.
struct RoundedInertia {
  int node = -1;
  int dof = 0;
  double ratio = 0.0;
};

/// A converged step whose stability round-off leaves unknown (negative_eigenvalues −1).
struct RoundedStep {
  int step = 0;
  RoundedInertia pivot;
};

/// A converged step in neutral equilibrium: the motion its supports leave free (StepRecord::neutral).
struct NeutralStep {
  int step = 0;
  FreeMotion motion;
};

/// Where one stage of a staged run ended (Model::stages, in order; the stages run).
struct StageEnd {
  int stage = 0;              ///< its index (Model::stages)
  int last_step = 0;          ///< its newest converged step (0: none converged)
  double load_factor = 0.0;   ///< its λ there
  Status status = Status::converged;
};

struct RunResult {
  Status status = Status::converged;
  std::string message;  ///< a sentence when the run did not reach its end (diagnosis.hpp, from `failure`)
  RunFailure failure;   ///< why it did not, as facts
  std::vector<StepRecord> steps;
  std::vector<LimitPoint> limit_points;  ///< in path order
  std::vector<RefinedLimit> refined_limits;  ///< the limit points located, by the stepping
  std::vector<CriticalPoint> critical_points;  ///< bifurcations found under load control, in path order
  std::vector<NeutralStep> neutral_steps;      ///< in path order
  std::vector<RoundedStep> rounded_steps;      ///< in path order
  Buckling buckling;                           ///< linearised buckling at the unloaded state, if asked for
  /// Remarks on the path, converged or not: a sentence each (e.g. a jump across a snap-back
  /// under displacement control).
  std::vector<std::string> notes;
  std::vector<StageEnd> stages;  ///< a staged run's stages that ran (empty: no stages)
};

/// Called after every step, converged or failed (progress lines, logging).
using StepObserver = std::function<void(const StepRecord&)>;

}  // namespace tsm::solver
