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

#include "tsmframe/solver/dense_block_ldlt.hpp"

namespace tsm::solver {

using Block = Eigen::Matrix3d;

/// Symmetric block-sparse matrix: the lower triangle, block column by block column.
struct BlockMatrix {
  int size = 0;                 ///< number of block rows/columns
  std::vector<int> column;      ///< column c holds entries column[c] .. column[c+1]
  std::vector<int> row;         ///< block row of each entry (≥ c, ascending: diagonal first)
  std::vector<Block> value;     ///< 3×3 block of each entry: A(row, c)
  /// Per entry: 1 if add_fill added it (no entry of A). Its value is never read - the
  /// factorisation starts it at zero - so it need not be cleared between factorisations; other
  /// readers of the values skip it (is_fill). Empty: no fill.
  std::vector<unsigned char> fill;
  bool is_fill(int entry) const { return !fill.empty() && fill[entry] != 0; }
};

/// Extends the pattern of `matrix` (every column must hold its diagonal) by the fill of its
/// LDLᵀ factor, so that it can be factorised in place, and marks the added entries (fill); the
/// values become zero.
void add_fill(BlockMatrix& matrix);

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

  /// Negative eigenvalues of D in the last factorisation (the tangent's inertia, Sylvester):
  /// 0 for a positive definite tangent; more once a structure is past a limit or bifurcation
  /// point. Counted from each pivot block's leading minors.
  int negative_pivots() const {
    int total = negative_pivots_;
    for (const PerThread& t : thread_negatives_) total += t.count;
    return total;
  }

  /// Subtrees factorised (and solved) as parallel tasks, and the rows above them.
  int task_count() const { return static_cast<int>(task_start_.size()) - 1; }
  int rows_above_tasks() const { return static_cast<int>(top_rows_.size()); }
  /// Rows above the tasks formed in passes, as paths of the tree (see factorize).
  int rows_in_paths() const {
    int rows = 0;
    for (const Stage& s : stages_) rows += parallel_top_ && s.path ? s.end - s.begin : 0;
    return rows;
  }
  /// Rows of those paths whose block among themselves is factorised as a dense matrix.
  int rows_in_dense_paths() const {
    int rows = 0;
    for (const Stage& s : stages_) rows += s.dense ? s.end - s.begin : 0;
    return rows;
  }

 private:
  int size_ = 0;
  int negative_pivots_ = 0;  ///< see negative_pivots(): the dense top's, plus the rows' per thread
  struct alignas(64) PerThread {
    int count = 0;
  };
  std::vector<PerThread> thread_negatives_;
  const BlockMatrix* factor_ = nullptr;  ///< the matrix holding L and D⁻¹ after factorize
  // Row k of A's lower triangle (the entries (k, i), i < k, one in each column i): row_start_[k]
  // .. row_start_[k+1] in row_position_ (their index in value), columns ascending. Row k of L
  // has the same pattern.
  std::vector<int> row_start_;
  std::vector<int> row_position_;
  std::vector<int> row_column_;  ///< i of each entry
  std::vector<unsigned char> row_fill_;  ///< whether each entry is fill (zeroed as its row starts); empty: none
  std::vector<int> slot_;        ///< during row k: column i → index in value of the entry (k, i)
  // Parallel factorisation: disjoint subtrees of the elimination tree touch disjoint rows and
  // columns, so they are factorised concurrently; the rows above them follow level by level, a
  // level's rows concurrently where levels hold several. Every row is computed with the same
  // arithmetic in the same order whatever the number of threads: results are bit-identical.
  std::vector<int> task_start_;  ///< task t: rows task_rows_[task_start_[t] .. task_start_[t+1]), ascending
  std::vector<int> task_rows_;
  std::vector<int> top_rows_;    ///< rows in no task, level by level (ascending within a level)
  std::vector<int> level_start_; ///< level l: top_rows_[level_start_[l] .. level_start_[l+1])
  bool parallel_top_ = false;    ///< enough rows above the tasks to run their stages in parallel
  bool parallel_tasks_ = false;  ///< several tasks, in a matrix big enough to share out (util::smallest_shared_model)
  bool parallel_top_levels_ = false;  ///< the solves: the levels hold enough rows side by side
  bool team_ = false;  ///< a matrix big enough for the rows above the tasks to run on every thread (util::smallest_shared_model)
  /// Stages of top_rows_ [begin, end): a level of several rows, or a path of single-row levels.
  struct Stage {
    int begin = 0, end = 0;
    bool path = false;
    /// A path whose rows' entries from its first column on lie in its own columns and fill at
    /// least half of its lower triangle: that part is factorised as a dense matrix.
    bool dense = false;
  };
  std::vector<Stage> stages_;
  std::vector<int> split_;        ///< per entry of top_rows_ in a path: its first entry (row index t) in a path column
  std::vector<int> thread_slot_;  ///< one slot map per thread, for the path rows' prefixes
  std::vector<int> deferred_start_;  ///< per entry of top_rows_ in a path: its prefix's place in deferred_z_
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
  bool factorize_dense_path(BlockMatrix& a, const Stage& stage, double* forward);
};

}  // namespace tsm::solver
