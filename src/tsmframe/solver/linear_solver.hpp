#pragma once
// The linear solver of the Newton iteration: K_ff δD = R, K_ff = A + Σ u_k v_kᵀ with A the
// symmetric node-block tangent (node-block LDLᵀ, block_ldlt) and u_k v_kᵀ the non-symmetric
// sliding terms of active contact elements. Up to most_rank_one terms they are applied exactly
// by the Sherman–Morrison–Woodbury formula (one extra solve per contact); beyond, each is added
// into the blocks of its contact element's nodes and the whole is factorised by the node-block
// LU (block_lu: the same pattern, a second triangle). Where that cannot be done (an unpivoted
// pivot block singular), or A alone cannot be factorised (a structure held only through a
// contact's sliding term), the whole K_ff goes to Eigen's SparseLU. Vectors are over the free
// equations.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <Eigen/LU>
#include <Eigen/SparseLU>
#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "tsmframe/assembly/dof_map.hpp"
#include "tsmframe/linalg/block_ldlt.hpp"
#include "tsmframe/linalg/block_lu.hpp"
#include "tsmframe/linalg/rank_one.hpp"

namespace tsm::solver {

using linalg::BlockMatrix;
using linalg::RankOne;

class LinearSolver {
 public:
  /// Beyond this many rank-one terms one block LU is cheaper than an extra solve for each.
  static constexpr size_t most_rank_one = 32;
  /// Symbolic analysis of the tangent's block pattern (values ignored); done once.
  void analyze(const assembly::DofMap& dofs, const BlockMatrix& matrix);
  /// Refills `matrix` with the tangent as it was before a failed in-place factorisation (the
  /// Newton iteration evaluates it again): called only when the block LDLᵀ of A or the block LU
  /// of A + Σ u vᵀ fails while sliding terms are present, for the SparseLU of A + Σ u vᵀ.
  /// Keeping a copy of A instead would cost a copy of the tangent at every factorisation with
  /// contacts.
  using Refill = std::function<void(BlockMatrix&)>;
  /// Numeric factorisation of `matrix` + Σ u vᵀ; false if singular or not finite. The block
  /// LDLᵀ overwrites `matrix` with its factor (solves use it until the next factorisation).
  bool factorize(BlockMatrix& matrix, const std::vector<RankOne>& rank_one = {}, const Refill& refill = {});
  /// Factorises as factorize() and solves K x = b (`x` holds b on entry): without contact terms
  /// the forward substitution rides along the factorisation (one pass over the factor less).
  bool factorize_and_solve(BlockMatrix& matrix, const std::vector<RankOne>& rank_one, Eigen::VectorXd& x,
                           const Refill& refill = {});
  /// Whether the next factorisations guard their inertia against round-off (BlockLDLT::guard_inertia).
  void guard_inertia(bool on) { ldlt_.guard_inertia(on); }
  /// The inertia of the symmetric part A in the last factorisation (block LDLᵀ's; its rows are
  /// blocks, DofMap::block_node), none when the last factorisation was an LU (the block LU of
  /// A + Σ u vᵀ beyond most_rank_one terms, or the general SparseLU).
  std::optional<linalg::Inertia> inertia() const {
    if (general_ || block_lu_) return std::nullopt;
    return ldlt_.inertia();
  }
  /// Solves with the last factorisation.
  Eigen::VectorXd solve(const Eigen::VectorXd& rhs) const;
  /// Solves in place: `x` holds the right-hand side and receives the solution.
  void solve_in_place(Eigen::VectorXd& x) const;

 private:
  bool factorize_block_lu(BlockMatrix& matrix, const std::vector<RankOne>& rank_one);
  bool factorize_general(const BlockMatrix& matrix, const std::vector<RankOne>& rank_one);
  void solve_symmetric_in_place(Eigen::VectorXd& x) const;
  /// solve(b) on `x` laid out in blocks (3 entries per block, a constrained dof's place 0).
  template <class Solve>
  void in_blocks(Eigen::VectorXd& x, const Solve& solve) const;
  /// An equation's place among the blocks' entries.
  int place(int equation) const { return padding_needed_ ? padded_[equation] : equation; }

  linalg::BlockLDLT ldlt_;
  const assembly::DofMap* dofs_ = nullptr;
  bool general_ = false;  ///< the last factorisation is the SparseLU one
  bool block_lu_ = false;  ///< the last factorisation is the block LU of A + Σ u vᵀ
  linalg::BlockLU block_lu_factor_;
  bool block_lu_analyzed_ = false;
  std::vector<linalg::Block> upper_;  ///< the block LU's other triangle (BlockLU::factorize)
  /// A sliding term's entry in the block LU's matrix: its index in the term, its block and dof there.
  struct TermEntry {
    int index, block, dof;
  };
  /// A sliding term's nonzero u entries (rows) and v entries (columns), grouped by block, and the
  /// matrix entry of each pair of a row group and a column group (for_each_block_pair's order).
  struct TermPlan {
    std::vector<TermEntry> rows, columns;
    std::vector<int> blocks;
  };
  std::vector<TermPlan> term_plans_;  ///< one per term (their storage reused)
  /// Calls visit(i, i_end, j, j_end) for each run of rows [i, i_end) in one block and of columns
  /// [j, j_end) in one block.
  template <class Visit>
  static void for_each_block_pair(const TermPlan& plan, const Visit& visit) {
    for (size_t i = 0; i < plan.rows.size();) {
      size_t i_end = i + 1;
      while (i_end < plan.rows.size() && plan.rows[i_end].block == plan.rows[i].block) ++i_end;
      for (size_t j = 0; j < plan.columns.size();) {
        size_t j_end = j + 1;
        while (j_end < plan.columns.size() && plan.columns[j_end].block == plan.columns[j].block) ++j_end;
        visit(i, i_end, j, j_end);
        j = j_end;
      }
      i = i_end;
    }
  }
  /// The plan of term `t` on `matrix`'s pattern; false where a pair of blocks has no entry.
  bool plan_term(const linalg::BlockMatrix& matrix, const linalg::RankOne& t, TermPlan& plan) const;
  /// Adds term `t` into `matrix` (lower triangle) and upper_ by its plan.
  void add_term(linalg::BlockMatrix& matrix, const linalg::RankOne& t, const TermPlan& plan);
  Eigen::SparseMatrix<double> general_matrix_;
  std::unique_ptr<Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>>> lu_;
  // Woodbury: Z = A⁻¹ U (one column per contact), V (dense), and the LU of I + Vᵀ Z.
  Eigen::MatrixXd woodbury_z_, woodbury_v_;
  Eigen::PartialPivLU<Eigen::MatrixXd> woodbury_capacitance_;
  std::vector<int> padded_;  ///< per free equation: its place in the block-padded vector
  int padded_size_ = 0;
  bool padding_needed_ = true;  ///< some block has a constrained dof (else equations = padded places)
  mutable Eigen::VectorXd padded_work_;  ///< the block-padded right-hand side, reused by every solve
};

}  // namespace tsm::solver
