#pragma once
// Global internal force vector and tangent of the whole structure at a given displacement
// state. The tangent is kept as 3×3 node blocks (lower triangle, blocks in the DofMap's
// fill-reducing order) whose pattern is built once; every evaluation only writes values.
// Elements are evaluated in chunks along the tangent's memory order, chunks in colour groups
// (no two chunks of a group share a node), each group in parallel: every sum is formed in the
// same order whatever the number of threads, so results are bit-identical with 1 or many threads.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "tsmframe/assembly/contact_assembly.hpp"
#include "tsmframe/assembly/dof_map.hpp"
#include "tsmframe/assembly/follower_loads.hpp"
#include "tsmframe/assembly/nodal_springs.hpp"
#include "tsmframe/assembly/rounding_floor.hpp"
#include "tsmframe/contact/active_contact.hpp"
#include "tsmframe/contact/contact_set.hpp"
#include "tsmframe/element/beam_element.hpp"
#include "tsmframe/linalg/block_matrix.hpp"
#include "tsmframe/linalg/rank_one.hpp"
#include "tsmframe/model/model.hpp"
#include "tsmframe/model/nodal_frames.hpp"

namespace tsm::assembly {

using linalg::BlockMatrix;

/// What one evaluation of the structure yields.
struct Evaluation {
  Eigen::VectorXd internal_force;        ///< F = Σ J S over all dofs
  std::vector<double> chord_rotations;   ///< β per element at this state
  /// K_fp · D_p,ref over the free equations: how the tangent couples free dofs to the
  /// prescribed displacements (for the tangent predictor, FORMULATION §4). Empty when the model
  /// prescribes no displacement.
  Eigen::VectorXd prescribed_coupling;
  /// One entry per active contact, in the order they were given.
  std::vector<contact::ContactEvaluation> contacts;
  /// max |θ| over the plain elements' ends: how far an end turns against its chord.
  double largest_end_rotation = 0.0;
  /// The reference load at this state: Model::reference_load plus the follower loads (members'
  /// pressure) on the current geometry, at λ = 1. Empty when the model has no follower load
  /// (the reference load is then Model::reference_load, fixed).
  Eigen::VectorXd reference_load;
  /// The dead load at this state (an earlier stage's, held: Model::dead_load plus the dead
  /// follower loads on the current geometry). Empty when no dead load turns (it is then
  /// Model::dead_load, fixed, or none).
  Eigen::VectorXd dead_load;
  /// Which evaluation of its GlobalSystem filled it (they are numbered from 1): a contact change
  /// needs the tangent to be still this one's (GlobalSystem::evaluate_contact_change).
  std::uint64_t id = 0;
};

class GlobalSystem {
 public:
  GlobalSystem(const Model& model, const DofMap& dofs);

  const Model& model() const { return model_; }
  const DofMap& dofs() const { return dofs_; }
  const NodalFrames& frames() const { return frames_; }

  /// Evaluates every element at `displacements` (all dofs), continuing each chord rotation from
  /// `previous_rotations` (which may be out.chord_rotations itself: rotations continued in
  /// place). With `with_tangent`, the tangent (see tangent()) is overwritten.
  /// Each active contact replaces its beam element by the three-node contact element.
  /// At a skew roller (model/nodal_frames.hpp) the displacements are global and what the
  /// evaluation yields for the solver — forces, loads, tangent, sliding terms, the prescribed
  /// coupling — is in the node's frame (t, n).
  void evaluate(const Eigen::VectorXd& displacements, const std::vector<double>& previous_rotations,
                bool with_tangent, Evaluation& out, const std::vector<contact::ActiveContact>& contacts = {}) {
    evaluate(displacements, previous_rotations, with_tangent, out, contacts, false);
  }
  /// The same evaluation with another contact set, at the state of the last evaluate() with
  /// tangent into `out` (same displacements and previous rotations; the tangent not handed out for
  /// factorisation since). Only the elements at the nodes of the old and the new contacts are
  /// evaluated again, and only what they write at those nodes is formed again, in the loop's
  /// order: `out` and the tangent are bit for bit what evaluate() would give. The cost does not
  /// grow with the model (those elements, their chunks' end rotations, the entries only contacts
  /// write). Falls back to evaluate() when the state is not the last one's, the contacts need
  /// a larger pattern or a skew roller turns frames.
  void evaluate_contact_change(const Eigen::VectorXd& displacements, const std::vector<double>& previous_rotations,
                               Evaluation& out, const std::vector<contact::ActiveContact>& contacts);

  /// λ at which the next evaluations take place: the follower loads' stiffness −λ ∂P/∂D joins
  /// the tangent (only models with follower loads depend on it).
  void set_load_factor(double load_factor) { load_factor_ = load_factor; }

  /// K_ff from the last evaluation with tangent, as node blocks; the rows and columns of a
  /// block's constrained dofs are zero with 1 on the diagonal (they carry no equation). The
  /// pattern holds the fill of its LDLᵀ factor: entries no element couples, marked
  /// (BlockMatrix::is_fill) and left as they are - the factorisation starts them at zero - so a
  /// reader of the values skips them.
  const BlockMatrix& tangent() const { return tangent_; }
  /// The same storage, for the linear solver to factorise in place: after that it holds the
  /// factor, not K_ff, until the next evaluation with tangent.
  BlockMatrix& tangent_for_factorisation() {
    tangent_of_ = 0;  // no longer an evaluation's tangent: a contact change re-evaluates all
    return tangent_;
  }
  /// Element forces (N, M_i, M_j) per element, stacked, at a state (chord rotations of that
  /// state's evaluation; a contact's element gives its contact element's): a pass of its own,
  /// for the results only — the Newton iterations never store them.
  Eigen::VectorXd element_forces(const Eigen::VectorXd& displacements, const std::vector<double>& rotations,
                                 const std::vector<contact::ActiveContact>& contacts) const;
  /// The rounding floor at a state (chord rotations of that state's evaluation): a pass over the
  /// elements of its own, asked for only when Newton stagnates.
  RoundingFloor rounding_floor(const Eigen::VectorXd& displacements, const std::vector<double>& rotations,
                               const std::vector<contact::ActiveContact>& contacts) const;
  /// The contact elements' sliding terms from the same evaluation: K_ff = tangent() + Σ u vᵀ
  /// (their symmetric parts are in tangent()).
  const std::vector<linalg::RankOne>& contact_rank_one() const { return contact_rank_one_; }
  /// The slipping and sticking contacts' friction terms (friction.hpp, F14), not optional like
  /// the sliding terms: a slipping point's friction follows its normal force, as stiff as the
  /// contact itself.
  const std::vector<linalg::RankOne>& friction_rank_one() const { return friction_rank_one_; }
  /// Each active contact's (in `contacts`' order) point load direction and stiffness at `displacements`.
  std::vector<ContactDirection> contact_directions(const Eigen::VectorXd& displacements, const std::vector<double>& rotations,
                                                   const std::vector<contact::ActiveContact>& contacts) const;
  /// The follower loads' stiffness where it is not symmetric (the nodes where a loaded stretch
  /// ends: a free end, a change of pressure), as rank-one terms: K_ff = tangent() + Σ u vᵀ,
  /// exactly, beside the contacts' sliding terms. Empty where the load is conservative.
  const std::vector<linalg::RankOne>& follower_rank_one() const { return follower_rank_one_; }
  /// Changes whenever the block pattern of tangent() is rebuilt (a contact couples new nodes):
  /// the linear solver must analyse it again.
  int pattern_version() const { return pattern_version_; }
  /// At the next evaluation with tangent, the pattern keeps only the node pairs that contacts
  /// in touch there join (ensure_contact_pattern). Without it every pair a contact ever joined
  /// stays, and a pair Newton's wandering iterates joined far apart in the elimination order
  /// fills the factor between them for the rest of the run (the 500-m press's factorisation
  /// grew from 2 to 100 ms). The tangent's values and the elimination order stay; the factor's
  /// schedule follows the pattern, so its rounding may change.
  void forget_contact_pairs() { forget_contact_pairs_ = true; }

 private:
  /// The element at place q of the loop (element_order_[q]); returns its max |θ_i|, |θ_j| (0 if a
  /// contact element stands in for it). With `only_contact_nodes` (a contact change) it writes
  /// only what touches a node marked in contact_node_.
  /// Asks the cache for what place q's element will read and write (its nodes' displacements
  /// and forces, its tangent blocks); changes nothing.
  void prefetch_element(int q, const Eigen::VectorXd& displacements, bool with_tangent, const Evaluation& out) const;
  static constexpr int prefetch_distance = 8;  ///< places ahead of the element evaluated
  template <bool only_contact_nodes = false>
  double evaluate_element(int q, const Eigen::VectorXd& displacements, const std::vector<double>& previous_rotations,
                          bool with_tangent, Evaluation& out);
  /// max |θ_i|, |θ_j| of place q's element (0 if a contact element stands in), nothing written.
  double end_rotation(int q, const Eigen::VectorXd& displacements, const std::vector<double>& previous_rotations) const;
  /// evaluate(), told whether the displacements are the last evaluation's (a contact change).
  void evaluate(const Eigen::VectorXd& displacements, const std::vector<double>& previous_rotations, bool with_tangent,
                Evaluation& out, const std::vector<contact::ActiveContact>& contacts, bool same_displacements);
  /// The contacts' sums after the elements: contact elements, masks of the constrained dofs. With
  /// `same_displacements` (a contact change), a one-point contact whose kept response stands for
  /// it is not formed again.
  void finish_evaluation(const Eigen::VectorXd& displacements, const std::vector<double>& previous_rotations,
                         bool with_tangent, Evaluation& out, const std::vector<contact::ActiveContact>& contacts,
                         bool same_displacements = false);
  /// Per node, the places q of its elements in the loop's order (for contact changes; built on
  /// the first one).
  void list_node_elements();
  void mask_constrained_dofs();
  /// The evaluation's vectors and tangent into the skew rollers' frames (before the masks).
  void turn_to_nodal_frames(Evaluation& out, bool with_tangent);
  /// Adds `value`, a global row `dof`'s share of K_fp D_p, to its free equation (a skew roller's
  /// translation rows join its t equation).
  void add_coupling(int dof, double value, Eigen::VectorXd& coupling) const {
    const NodalFrames::Share share = frames_.row_share(dof);
    if (const int row = dofs_.equation(share.nodal_dof); row >= 0) coupling[row] += share.weight * value;
  }
  /// Marks the first writers (ElementRecord) and lists what no element writes; after every
  /// change of the pattern or of the loop's order.
  void mark_first_writers();
  void build_pattern();
  int entry(int block_row, int block_column) const;  ///< index in tangent_ of a lower entry (row ≥ column), −1 if absent
  void ensure_contact_pattern(const std::vector<contact::ActiveContact>& contacts);
  void add_block(int node_a, int node_b, const Eigen::Matrix3d& value);
  /// A contact element's response (contact_element_response) added to `out`: its forces, blocks and
  /// sliding terms.
  /// The tangent's entries of a contact element's node pairs (i, j, then its points' nodes; pairs
  /// p ≤ q in order): 2·entry, +1 where the lower triangle holds the pair transposed, −1 where a
  /// node has no block or repeats. Read-only: formed with the responses, in parallel.
  void contact_blocks(const contact::ActiveContact& contact, std::vector<int>& blocks) const;
  void prefetch_contact_blocks(const std::vector<int>& blocks) const;
  /// (Response: a contact of one point's ContactResponse, of several points' MultiPointResponse.)
  template <class Response>
  void add_contact(const contact::ActiveContact& contact, const Response& response, const std::vector<int>& blocks,
                   bool with_tangent, Evaluation& out);
  NodalFrames frames_;                              ///< the skew rollers' frames (empty: none)
  FollowerLoads follower_loads_;                    ///< the members' pressure (assembly/follower_loads)
  NodalSprings springs_;                            ///< springs to the ground (assembly/nodal_springs)
  std::vector<linalg::RankOne> follower_rank_one_;  ///< follower_rank_one()
  double load_factor_ = 0.0;                        ///< set_load_factor

  const Model& model_;
  const DofMap& dofs_;
  /// A hinged or sprung element's k0 with its releases and springs condensed
  /// (element::connected_stiffness), and its end springs' flexibilities 1/k (0: none).
  struct Connection {
    element::Matrix3 k;
    double flexibility_i = 0.0, flexibility_j = 0.0;
  };
  /// What the element loop reads of one element, in one record (one stream through memory):
  /// 80 bytes, no alignment padding (the chord's Δ0 is kept as two plain doubles).
  struct ElementRecord {
    int start = 0, end = 0;  ///< node indices
    /// Entries of its (i,i), (j,j) and (i,j) blocks in tangent_ (−1: node not a block). The
    /// (i,j) entry is stored as K_ji = K_ijᵀ when j's block is the larger (lower triangle).
    int ii = -1, jj = -1, ij = -1;
    bool transposed : 1 = false;
    /// First writer (in the loop's fixed order) of its (i,i), (j,j), (i,j) block and of node i's
    /// and j's internal forces: it assigns instead of adding, so nothing is cleared before the
    /// loop (0 + a = a exactly: the sums are the same as with clearing).
    bool first_ii : 1 = false, first_jj : 1 = false, first_ij : 1 = false, first_i : 1 = false, first_j : 1 = false;
    bool release_i : 1 = false, release_j : 1 = false;  ///< a hinge at that end (Element::release_start/end)
    bool connected : 1 = false;  ///< hinged or sprung at an end: its k0 is connections_[q].k (condensed)
    double delta0[2] = {0.0, 0.0};      ///< X_j − X_i
    double length = 0.0, angle = 0.0;   ///< l0, φ0
    element::BasicStiffness k0;         ///< Eq. 3 / 4, fixed (without its releases)
    element::InitialChord chord() const {
      return {element::Vector2::Zero(), element::Vector2(delta0[0], delta0[1]), length, angle};
    }
    /// k0 as the element uses it: its connection's (releases and springs condensed;
    /// GlobalSystem::connection, null where it has none) or the fixed form.
    element::Matrix3 stiffness(const Connection* connection) const { return connection ? connection->k : k0.matrix(); }
    /// The element's response: the common case on the fixed-form k0, a hinged or sprung element
    /// on its condensed one.
    element::BeamResponse respond(const element::Vector6& d, double previous_rotation, bool with_tangent,
                                  const Connection* connection) const {
      if (connection) return element::beam_response(chord(), connection->k, d, previous_rotation, with_tangent);
      return element::beam_response(chord(), k0, d, previous_rotation, with_tangent);
    }
    /// The larger end rotation against the chord that the element describes (a hinged end's
    /// rotation is not the element's: it is left out; an end spring's turn M/k is taken off the
    /// node's, `connection` the element's springs or null).
    double end_rotation(const element::BeamResponse& r, const Connection* connection) const {
      if (!connection) return std::max(std::abs(r.deformations[1]), std::abs(r.deformations[2]));  // neither hinged nor sprung
      return connected_end_rotation(r, *connection);
    }
    double connected_end_rotation(const element::BeamResponse& r, const Connection& connection) const;
  };
  static_assert(sizeof(ElementRecord) == 80, "no padding: the element loop streams these records");
  /// Per place q of the loop, a hinged or sprung element's (ElementRecord::connected) condensed k0
  /// and its springs' flexibilities; empty when the model has none.
  std::vector<Connection> connections_;
  const Connection* connection(int q) const { return records_[q].connected ? &connections_[q] : nullptr; }
  std::vector<ElementRecord> records_;  ///< in the loop's order: records_[q] is element element_order_[q]
  BlockMatrix tangent_;
  std::vector<unsigned char> block_mask_;  ///< per block: bit d set if dof d of its node is constrained
  std::vector<int> element_order_;  ///< element indices in the tangent's memory order
  std::vector<int> chunk_start_;    ///< chunk h: element_order_[chunk_start_[h] .. chunk_start_[h+1])
  std::vector<int> colour_chunks_;  ///< chunk numbers, grouped by colour
  std::vector<int> colour_start_;   ///< group c: colour_chunks_[colour_start_[c] .. colour_start_[c+1])
  std::vector<double> chunk_largest_end_rotation_;  ///< per chunk, in the last evaluation
  bool has_prescribed_ = false;
  std::vector<int> unwritten_entries_;     ///< tangent entries no element writes but contacts may (contact-only pairs): cleared
  std::vector<int> unwritten_nodes_;       ///< nodes no element joins: their internal forces cleared
  std::vector<char> replaced_;             ///< per element: carries a contact in this evaluation
  std::vector<linalg::RankOne> contact_rank_one_;
  /// finish_evaluation's scratch, kept so that its storage is reused: a chunk of contacts'
  /// responses, a contact element's dofs, nodes and equations, and how many of contact_rank_one_
  /// the evaluation has filled.
  std::vector<contact::MultiPointResponse> contact_responses_;
  std::vector<contact::ContactResponse> point_responses_;  ///< … those of one point, in their fixed-size form
  std::vector<KeptPointResponse> kept_responses_;  ///< per contact: its one-point response, kept (finish_evaluation)
  std::vector<std::vector<int>> contact_blocks_;  ///< contact_blocks of each response in contact_responses_
  std::vector<int> contact_dofs_, contact_equations_;
  size_t contact_rank_ones_ = 0;
  std::vector<linalg::RankOne> friction_rank_one_;
  size_t friction_rank_ones_ = 0;
  std::vector<std::pair<int, int>> contact_pairs_;  ///< node pairs joined only by contact elements
  bool forget_contact_pairs_ = false;                ///< see forget_contact_pairs()
  int pattern_version_ = 0;
  std::vector<std::pair<int, int>> turned_entries_;  ///< (entry, block column) touching a skew roller's node
  int turned_version_ = -1;                          ///< pattern version turned_entries_ was listed for
  std::vector<std::pair<int, int>> masked_entries_;  ///< (entry, block column) touching a constrained dof
  int masked_version_ = -1;                          ///< pattern version masked_entries_ was listed for
  // What a contact change needs of the last evaluation (evaluate_contact_change).
  std::uint64_t evaluations_ = 0;  ///< evaluations so far: each one's Evaluation::id
  std::uint64_t tangent_of_ = 0;   ///< the id of the evaluation the tangent belongs to (0: none)
  std::vector<int> last_contact_nodes_;  ///< the nodes of the contacts it was evaluated with (each contact's i, j, points)
  std::vector<int> chunk_rank_;              ///< per chunk, its place in the loop's order
  std::vector<int> node_element_start_;      ///< node k: node_elements_[start[k] .. start[k+1])
  std::vector<int> node_elements_;           ///< places q, per node in the loop's order
  std::vector<char> contact_node_;           ///< per node: a node of an old or new contact (during a change)
};

}  // namespace tsm::assembly
