#pragma once
// The structure a user describes, after reading and meshing: nodes, elements, supports, loads,
// prescribed displacements, contacts and analysis settings. Plain, validated data; no mechanics.

#include <Eigen/Core>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "tsmframe/element/force_law.hpp"

namespace tsm {

/// Degrees of freedom of a node, in the order they are stored: (u, v, θ).
enum Dof : int { ux = 0, uy = 1, rz = 2 };
inline constexpr int dofs_per_node = 3;
const char* dof_name(int dof);

enum class BeamTheory { euler_bernoulli, timoshenko };
const char* theory_name(BeamTheory theory);

struct Node {
  int id = 0;
  Eigen::Vector2d position;
};

struct Element {
  int id = 0;       ///< 1-based, in generation order
  int start = 0;    ///< index of node i (not its id)
  int end = 0;      ///< index of node j
  int member = 0;   ///< index of the member it was generated from
  BeamTheory theory = BeamTheory::euler_bernoulli;
  /// A hinge at that end: the element carries no moment there (M_i or M_j = 0, its end rotation
  /// condensed out of k0), so the node's rotation is not the element's.
  bool release_start = false, release_end = false;
  /// It starts / ends its member: the member's end springs (MemberExtras) are its.
  bool member_start = false, member_end = false;
  element::SectionStiffness section;
};

/// What a member adds to its elements beside their section, rare enough to be kept per member
/// (a field per element costs 0.8 MB at 10⁵ elements).
struct MemberExtras {
  /// Follower load (pressure) per unit current length, scaled by λ: normal to each current
  /// element chord, pushing from the member's left side (seen from `from` to `to`) towards its
  /// right — down on a member drawn left to right. Lumped half to each element end. 0: none.
  double pressure = 0.0;
  /// A rotational spring between the member's first / last element and its node (a semi-rigid
  /// connection): its flexibility 1/k, moment per radian inverted (0: rigid, the usual joint).
  double flexibility_from = 0.0, flexibility_to = 0.0;
  /// The pressure an earlier stage applied, held at its final level (not scaled by λ; stage.hpp).
  double dead_pressure = 0.0;
};

/// An element's end displacements (u, v, θ)_i, (u, v, θ)_j out of all dofs' D. Each node's
/// (u, v) is copied as one pair: the chord reads them as pairs, and a pair read back from two
/// single stores waits for both to reach the cache (no store-to-load forwarding), a stall in
/// the element loop's hot path (bench/README.md measures it).
inline Eigen::Matrix<double, 6, 1> element_displacements(const Eigen::VectorXd& D, int start, int end) {
  Eigen::Matrix<double, 6, 1> d;
  d.segment<2>(0) = D.segment<2>(dofs_per_node * start);
  d[2] = D[dofs_per_node * start + rz];
  d.segment<2>(3) = D.segment<2>(dofs_per_node * end);
  d[5] = D[dofs_per_node * end + rz];
  return d;
}

/// The frame a contact element is written in: the chord's (Eq. 6–9) or the cantilever's
/// clamped at node i (FORMULATION §2b).
enum class ContactFrame { chord, cantilever };
/// Which normal a frictionless contact force acts along: the element's chord's (the paper's,
/// Eq. 6–9) or its deflected shape's at the contact point (docs/contact-normal.md; issue 27).
enum class ContactNormal { chord, deflected };

/// Whether contacts in frames `a` and `b` may have points on one element: an element carries any
/// number of points (issue 27), all written in one frame (the chord's points of either normal).
inline bool shares_element(ContactFrame a, ContactFrame b) { return a == b; }

struct ContactSpec {
  int node = 0;                 ///< contact node index
  std::vector<int> members;     ///< member indices the node may touch
  /// The contact law's beam theory where it overrides the touched element's (none: follow it).
  std::optional<BeamTheory> theory;
  ContactFrame frame = ContactFrame::chord;
  ContactNormal normal = ContactNormal::deflected;
  double gap = 0.0;             ///< distance from the centre line at which contact starts
  double edge = -1.0;           ///< compliance clamp zone (contact_force_law); < 0: default per theory
  /// The contact at most this many times as stiff as the stiffest element holding its node, in
  /// the contact's direction (EA/l0 along an element, 12EI/l0³ across it): a compliance floor
  /// that keeps rounding resolvable on far stiffer members.
  double max_stiffness_ratio = 1e4;
  bool sliding_tangent = true;  ///< consistent tangent (false: leave the sliding term out)
  /// Coulomb's μ along the touched beam (docs/friction.md; 0: frictionless, today's contact).
  double friction = 0.0;
  /// Per member: Ψ for a "timoshenko" override (members drawn as Euler–Bernoulli included).
  std::vector<double> member_shear_flexibility;
};

enum class ControlType { load, displacement, arc_length };

struct Control {
  ControlType type = ControlType::load;
  int steps = 1;         ///< steps per leg of the path
  /// Load control: λ visits these values in turn from 0 (empty: just 1), `steps` per leg.
  std::vector<double> path;
  // displacement control: node index, dof, target value
  int node = -1;
  int dof = uy;
  double target = 0.0;
  /// The controlled dof's value where the path starts (an earlier stage's end; 0 otherwise):
  /// the steps run from it to `target`.
  double start = 0.0;
  // arc-length control (docs/format.md): arc length of the first step, bounds, step budget, and when
  // to stop (a load factor, or a value of one dof, reached in either direction)
  double initial_increment = 0.0;
  double min_increment = 0.0;
  double max_increment = 0.0;
  int max_steps = 0;
  enum class Until { steps, load_factor, displacement } until = Until::steps;
  double until_value = 0.0;
  int until_node = -1;
  int until_dof = uy;
};

/// A nodal force that turns with its node (a follower point load): R(θ) force at the node's
/// rotation θ, scaled by λ like the reference load (`force`: as drawn, at θ = 0).
struct FollowerForce {
  int node = 0;  ///< node index
  Eigen::Vector2d force = Eigen::Vector2d::Zero();
  /// Applied by an earlier stage and held there: `force` in full, whatever λ (stage.hpp).
  bool dead = false;
};

/// A linear spring from a node to the ground (docs/format.md, "springs"): along a fixed unit
/// direction (a translation spring: force −k d (d·u)) or about the node's rotation (−k θ).
struct NodalSpring {
  int node = 0;  ///< node index
  enum class Kind { translation, rotation } kind = Kind::translation;
  Eigen::Vector2d direction = Eigen::Vector2d::UnitX();  ///< unit; translation springs
  double stiffness = 0.0;                                ///< > 0: force per length, or moment per radian
};

/// A support on an inclined plane (a skew roller): the node rolls along `along` (unit) and is held
/// normal to it. Its translations are solved for in the roller's frame (t, n), t = along,
/// the n dof held (Model::constrained at its uy slot; model/nodal_frames.hpp).
struct SkewRoller {
  int node = 0;  ///< node index
  Eigen::Vector2d along = Eigen::Vector2d::UnitX();
};

struct OutputSelection {
  enum class Kind { all, last, every } kind = Kind::all;
  int every = 1;
};

struct AnalysisSettings {
  Control control;
  double tolerance = 1e-8;
  int max_iterations = 50;
  bool cutback = true;
  int max_cutbacks = 10;  ///< halvings in a row before the run gives up (docs/format.md)
  OutputSelection output;
  std::vector<int> monitor;  ///< node indices written to steps.csv
  /// Linearised buckling modes asked for (solver/buckling; 0: none), and where: at the unloaded
  /// state, at the run's last converged state, or at the converged step `buckling_step`.
  int buckling_modes = 0;
  enum class BucklingAt { unloaded, end, step } buckling_at = BucklingAt::unloaded;
  int buckling_step = 0;
  /// The number of the run's first step and the stage its steps belong to: 1 and 0, but for a
  /// staged run's later stages (stage.hpp) and a restart (solver/restart.hpp), numbered on.
  int first_step = 1;
  int stage = 0;
};

/// A displacement a stage prescribes at one dof: the value it reaches at the stage's end (λ = 1),
/// absolute or an increment on where the dof stands when the stage starts.
struct PrescribedTarget {
  int dof = 0;  ///< global dof (3 per node)
  double value = 0.0;
  bool increment = false;
};

/// One stage of a staged analysis (docs/format.md, "Stages"): the loads and prescribed
/// displacements it applies, scaled by its own load factor from 0 to where its control ends,
/// everything earlier stages applied held at their final level (stage.hpp).
struct Stage {
  std::string name;
  Eigen::VectorXd load;                      ///< per dof, nodal (empty: none)
  std::vector<FollowerForce> follower_forces;
  std::vector<PrescribedTarget> prescribed;  ///< dofs held from here on
  /// Per contact (Model::contacts): 1 where it does not exist in this stage — never in touch, let
  /// go at the stage's start (empty: every contact exists).
  std::vector<char> contact_off;
  Control control;
  OutputSelection output;
};

struct Model {
  std::string title;
  std::map<std::string, std::string> units;
  std::vector<Node> nodes;
  std::vector<Element> elements;
  int member_count = 0;
  std::vector<MemberExtras> member_extras;  ///< per member (empty: none has any)
  /// An element's follower load and end springs' flexibilities (MemberExtras), 0 where none.
  double pressure(const Element& e) const { return member_extras.empty() ? 0.0 : member_extras[e.member].pressure; }
  double dead_pressure(const Element& e) const { return member_extras.empty() ? 0.0 : member_extras[e.member].dead_pressure; }
  double flexibility_start(const Element& e) const {
    return member_extras.empty() || !e.member_start ? 0.0 : member_extras[e.member].flexibility_from;
  }
  double flexibility_end(const Element& e) const {
    return member_extras.empty() || !e.member_end ? 0.0 : member_extras[e.member].flexibility_to;
  }
  /// Per dof (3 per node): fixed or prescribed.
  std::vector<bool> constrained;
  /// Per dof: reference load, multiplied by the load factor λ.
  Eigen::VectorXd reference_load;
  /// Nodal forces that turn with their nodes, multiplied by λ too (not in reference_load).
  std::vector<FollowerForce> follower_forces;
  /// Per dof: the loads earlier stages applied, held at their final level whatever λ (empty:
  /// none; stage.hpp). The follower ones are in follower_forces and MemberExtras::dead_pressure.
  Eigen::VectorXd dead_load;
  /// Per dof: prescribed displacement reached at λ = 1 (zero where none); empty when no
  /// displacement is prescribed (a model's worth of zeros saved). Read it through prescribed().
  /// From an earlier stage's end, the increment on start_displacements.
  Eigen::VectorXd reference_prescribed;
  /// Per dof: the displacements the run starts from — an earlier stage's end (empty: the
  /// unloaded state). The constrained dofs stand there at λ = 0.
  Eigen::VectorXd start_displacements;
  std::vector<ContactSpec> contacts;
  std::vector<NodalSpring> springs;
  /// Supports on inclined planes, one per node at most; a roller along x or y is a plain support.
  std::vector<SkewRoller> skew_rollers;
  AnalysisSettings analysis;
  /// A staged analysis (empty: one stage, the loads and control above). The members' loads,
  /// pressures and self-weight (reference_load, MemberExtras) are the first stage's, with its own.
  std::vector<Stage> stages;
  /// A stage's model (stage_model): the dofs its staged model's moved_dofs() gives, so that every
  /// stage records the reactions at the same dofs (empty otherwise).
  std::vector<int> stage_moved_dofs;
  /// Diagonal of the bounding box of the nodes (1 if they all coincide).
  double size = 1.0;

  int node_count() const { return static_cast<int>(nodes.size()); }
  int dof_count() const { return dofs_per_node * node_count(); }
  /// An element's length as drawn (between its nodes).
  double drawn_length(const Element& e) const { return (nodes[e.end].position - nodes[e.start].position).norm(); }
  /// Prescribed displacement of a dof at λ = 1 (0 when reference_prescribed is empty).
  double prescribed(int dof) const { return reference_prescribed.size() > 0 ? reference_prescribed[dof] : 0.0; }
  /// A constrained dof's displacement at load factor λ: its start plus λ times its increment.
  double prescribed_at(int dof, double load_factor) const {
    const double moved = load_factor * prescribed(dof);
    return start_displacements.size() > 0 ? start_displacements[dof] + moved : moved;
  }
  /// Index of the node with this id, or −1.
  int node_index(int id) const;
  /// The dofs a prescribed displacement moves (nonzero at λ = 1), ascending; with stages, every
  /// dof a stage prescribes.
  std::vector<int> moved_dofs() const;
};

}  // namespace tsm
