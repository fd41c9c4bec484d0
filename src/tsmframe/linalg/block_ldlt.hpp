#pragma once
// Sparse LDLᵀ factorisation over 3×3 node blocks, for the symmetric TSM tangent, in place.
//
// Frames are node-blocked by nature (every element couples two nodes' (u, v, θ)), so working
// on dense 3×3 blocks instead of scalars removes most of a scalar sparse factorisation's index
// bookkeeping. The blocks are numbered in a fill-reducing order chosen once (DofMap). The
// matrix is kept as its lower triangle by columns, and its pattern already holds the fill of
// the factor (add_fill, once per pattern), so the factor overwrites the matrix: column i
// becomes column i of L below the diagonal and D_i⁻¹ on it — no second copy of the tangent's
// size, and the factorisation's inner loop and both triangular solves stream through columns.
// D is block diagonal with 3×3 symmetric blocks inverted exactly, so the factorisation also
// handles indefinite tangents (past a limit point) as long as no 3×3 pivot block is singular.
// Up-looking algorithm as in CSparse's cs_chol, lifted to blocks. The arithmetic order is
// fixed: results do not depend on threads. Independent subtrees of the elimination tree, and
// rows above them that are not ancestors of one another, are factorised in parallel (OpenMP);
// the top separator, where the factor is dense, as one dense matrix (dense_block_ldlt). Entries
// added as fill are zeroed by the factorisation as their row starts, never read before.

#include <Eigen/Core>
#include <vector>

#include "tsmframe/linalg/block_ldlt_schedule.hpp"
#include "tsmframe/linalg/block_matrix.hpp"
#include "tsmframe/linalg/dense_block_ldlt.hpp"
#include "tsmframe/linalg/inertia.hpp"

namespace tsm::linalg {

class BlockLDLT {
 public:
  /// Elimination tree and the row structure of L from the pattern of `matrix`, which must
  /// already hold its fill (add_fill).
  void analyze(const BlockMatrix& matrix);
  /// Numeric factorisation, overwriting `matrix` (kept by reference for solve_in_place); false if
  /// a pivot block is singular or not finite. With `forward` (b, 3 entries per block), the
  /// forward substitution rides along, row by row while the row is in cache: on return it holds
  /// y = L⁻¹ b, for finish_solve.
  bool factorize(BlockMatrix& matrix, Eigen::VectorXd* forward = nullptr);
  /// Solves A x = b in place with the last factorisation; b has 3 entries per block.
  void solve_in_place(Eigen::VectorXd& b) const;
  /// Completes a solve whose forward substitution ran with factorize: x = L⁻ᵀ D⁻¹ y, in place.
  void finish_solve(Eigen::VectorXd& y) const;

  /// Whether factorize() checks each pivot for eigenvalues within round-off of zero
  /// (inertia.hpp): where the inertia is read as the stability of an equilibrium. Off, the count
  /// is taken as it comes (a few per cent of a chain's factorisation less).
  void guard_inertia(bool on) { guard_inertia_ = on; }
  /// The inertia of D in the last factorisation (the tangent's, Sylvester): 0 negative
  /// eigenvalues for a positive definite tangent; more once a structure is past a limit or
  /// bifurcation point; with the guard on, unknown where a pivot is within round-off of zero
  /// (inertia.hpp). Its row: a block row.
  Inertia inertia() const {
    Inertia total = dense_inertia_;
    for (const PerThread& t : thread_inertia_) total.add(t.inertia);
    return total;
  }
  /// Negative eigenvalues of D in the last factorisation, whether or not round-off leaves them in doubt.
  int negative_pivots() const { return inertia().negative; }

  /// Subtrees factorised (and solved) as parallel tasks, and the rows above them.
  int task_count() const { return rows_.schedule.task_count(); }
  int rows_above_tasks() const { return static_cast<int>(rows_.schedule.top_rows.size()); }
  /// Rows above the tasks formed in passes, as paths of the tree (see factorize).
  int rows_in_paths() const {
    int rows = 0;
    for (const BlockLDLTSchedule::Stage& s : rows_.schedule.stages) rows += rows_.schedule.parallel_top && s.path ? s.end - s.begin : 0;
    return rows;
  }
  /// Rows of those paths whose block among themselves is factorised as a dense matrix.
  int rows_in_dense_paths() const {
    int rows = 0;
    for (const BlockLDLTSchedule::Stage& s : rows_.schedule.stages) rows += s.dense ? s.end - s.begin : 0;
    return rows;
  }

 private:
  int size_ = 0;
  bool guard_inertia_ = false;
  Inertia dense_inertia_;  ///< see inertia(): the dense top's, plus the rows' per thread
  struct alignas(64) PerThread {
    Inertia inertia;
  };
  std::vector<PerThread> thread_inertia_;
  /// The diagonal of each block row's A_kk, kept as the row starts: what its pivot is measured against.
  std::vector<Eigen::Vector3d> original_diagonal_;
  std::vector<Eigen::Vector3d> dense_original_;  ///< original_diagonal_ of a dense path's rows, in its order
  const BlockMatrix* factor_ = nullptr;  ///< the matrix holding L and D⁻¹ after factorize
  // A's filled lower triangle by rows (row k of L has the same pattern), the slot map and the
  // schedule. Parallel factorisation: disjoint subtrees of the elimination tree touch disjoint
  // rows and columns, so they are factorised concurrently; the rows above them follow level by
  // level, a level's rows concurrently where levels hold several. Every row is computed with the
  // same arithmetic in the same order whatever the number of threads: results are bit-identical.
  FactorRows rows_;
  std::vector<int> thread_slot_;  ///< one slot map per thread, for the path rows' prefixes
    std::vector<Block> deferred_z_;    ///< running sums z of the path rows' prefix entries
  Eigen::MatrixXd dense_;            ///< a dense path's block, gathered, factorised and put back
  DenseBlockLDLT dense_ldlt_;

  /// Forms entries [t_begin, t_end) of row k (see block_ldlt.cpp); `finish` completes the row.
  bool form_row(BlockMatrix& a, int k, int t_begin, int t_end, double* forward, int* slot, bool finish, int defer_from,
                Block* deferred);
  /// Adds to row k the updates form_row left out (into rows ≥ defer_from), from its first t_end entries.
  void apply_deferred(BlockMatrix& a, int k, int t_end, int defer_from, const Block* deferred, int* slot) const;
  bool factorize_row(BlockMatrix& a, int k, double* forward);
  /// The rest of a dense path's rows (after the passes over their prefixes): gathered into dense_,
  /// factorised by all threads of the calling team together, put back. False if a pivot fails.
  bool factorize_dense_path(BlockMatrix& a, const BlockLDLTSchedule::Stage& stage, double* forward);
};

}  // namespace tsm::linalg
