#include "tsmframe/solver/linear_solver.hpp"

#include <algorithm>
#include <atomic>

#include "tsmframe/util/parallel_for.hpp"

namespace tsm::solver {

void LinearSolver::analyze(const assembly::DofMap& dofs, const BlockMatrix& matrix) {
  dofs_ = &dofs;
  padded_.resize(dofs.free_count());
  for (int eq = 0; eq < dofs.free_count(); ++eq) {
    const int dof = dofs.dof(eq);
    padded_[eq] = dofs_per_node * dofs.block(dof / dofs_per_node) + dof % dofs_per_node;
  }
  padded_size_ = dofs_per_node * dofs.block_count();
  padding_needed_ = padded_size_ != dofs.free_count();
  for (int eq = 0; eq < dofs.free_count() && !padding_needed_; ++eq) padding_needed_ = padded_[eq] != eq;
  if (!padding_needed_) std::vector<int>().swap(padded_);  // the identity: not kept
  ldlt_.analyze(matrix);
  block_lu_analyzed_ = false;  // analysed when first needed
}

bool LinearSolver::factorize(BlockMatrix& matrix, const std::vector<RankOne>& rank_one, const Refill& refill) {
  woodbury_z_.resize(0, 0);
  general_ = block_lu_ = false;
  if (rank_one.size() > most_rank_one) {
    if (factorize_block_lu(matrix, rank_one)) return true;
    // A pivot block the unpivoted LU cannot take, or a term outside the pattern: the general LU,
    // of the tangent the in-place factorisation has overwritten.
    block_lu_ = false;
    if (!refill) return false;
    refill(matrix);
    general_ = true;
    return factorize_general(matrix, rank_one);
  }
  // With contacts, A alone may be singular while A + Σ u vᵀ is not: the fallback needs A again
  // (the in-place factorisation has overwritten it).
  if (!ldlt_.factorize(matrix)) {
    if (rank_one.empty() || !refill) return false;
    refill(matrix);
    general_ = true;
    return factorize_general(matrix, rank_one);
  }
  if (rank_one.empty()) return true;
  const Eigen::Index n = static_cast<Eigen::Index>(dofs_->free_count()), q = static_cast<Eigen::Index>(rank_one.size());
  woodbury_z_.resize(n, q);
  woodbury_v_.setZero(n, q);
  for (Eigen::Index k = 0; k < q; ++k) {
    Eigen::VectorXd u = Eigen::VectorXd::Zero(n);
    for (int a = 0; a < rank_one[k].size(); ++a) {
      const int eq = rank_one[k].equation[a];
      if (eq < 0) continue;
      u[eq] += rank_one[k].u[a];
      woodbury_v_(eq, k) += rank_one[k].v[a];
    }
    solve_symmetric_in_place(u);
    woodbury_z_.col(k) = u;
  }
  const Eigen::MatrixXd capacitance = Eigen::MatrixXd::Identity(q, q) + woodbury_v_.transpose() * woodbury_z_;
  if (!capacitance.allFinite()) return false;
  woodbury_capacitance_.compute(capacitance);
  const double det = woodbury_capacitance_.determinant();
  return det != 0.0 && std::isfinite(det);
}

bool LinearSolver::factorize_and_solve(BlockMatrix& matrix, const std::vector<RankOne>& rank_one, Eigen::VectorXd& x,
                                       const Refill& refill) {
  if (!rank_one.empty()) {
    if (!factorize(matrix, rank_one, refill)) return false;
    solve_in_place(x);
    return true;
  }
  woodbury_z_.resize(0, 0);
  general_ = block_lu_ = false;
  if (!padding_needed_) {
    if (!ldlt_.factorize(matrix, &x)) return false;
    ldlt_.finish_solve(x);
    return true;
  }
  padded_work_.setZero(padded_size_);
  for (Eigen::Index eq = 0; eq < x.size(); ++eq) padded_work_[padded_[eq]] = x[eq];
  if (!ldlt_.factorize(matrix, &padded_work_)) return false;
  ldlt_.finish_solve(padded_work_);
  for (Eigen::Index eq = 0; eq < x.size(); ++eq) x[eq] = padded_work_[padded_[eq]];
  return true;
}

bool LinearSolver::plan_term(const BlockMatrix& matrix, const RankOne& t, TermPlan& plan) const {
  plan.rows.clear();
  plan.columns.clear();
  plan.blocks.clear();
  for (int a = 0; a < t.size(); ++a) {
    if (t.equation[a] < 0) continue;
    const int pa = place(t.equation[a]);
    const TermEntry entry_of_a{a, pa / dofs_per_node, pa % dofs_per_node};
    if (t.u[a] != 0.0) plan.rows.push_back(entry_of_a);
    if (t.v[a] != 0.0) plan.columns.push_back(entry_of_a);
  }
  // One search per pair of blocks: a term's entries come a node's dofs at a time.
  for_each_block_pair(plan, [&](size_t i, size_t, size_t j, size_t) {
    const int r = std::max(plan.rows[i].block, plan.columns[j].block), c = std::min(plan.rows[i].block, plan.columns[j].block);
    const auto begin = matrix.row.begin() + matrix.column[c], end = matrix.row.begin() + matrix.column[c + 1];
    const auto at = std::lower_bound(begin, end, r);
    const int p = at != end && *at == r ? static_cast<int>(at - matrix.row.begin()) : -1;
    plan.blocks.push_back(p >= 0 && !matrix.is_fill(p) ? p : -1);
  });
  return std::find(plan.blocks.begin(), plan.blocks.end(), -1) == plan.blocks.end();
}

void LinearSolver::add_term(BlockMatrix& matrix, const RankOne& t, const TermPlan& plan) {
  size_t pair = 0;
  for_each_block_pair(plan, [&](size_t i, size_t i_end, size_t j, size_t j_end) {
    const int p = plan.blocks[pair++];
    const bool lower = plan.rows[i].block >= plan.columns[j].block;
    for (size_t x = i; x < i_end; ++x)
      for (size_t y = j; y < j_end; ++y) {
        const double value = t.u[plan.rows[x].index] * t.v[plan.columns[y].index];
        if (lower) matrix.value[p](plan.rows[x].dof, plan.columns[y].dof) += value;
        else upper_[p](plan.columns[y].dof, plan.rows[x].dof) += value;
      }
  });
}

bool LinearSolver::factorize_block_lu(BlockMatrix& matrix, const std::vector<RankOne>& rank_one) {
  if (!block_lu_analyzed_) {
    block_lu_factor_.analyze(matrix);
    block_lu_analyzed_ = true;
  }
  // A is symmetric: its upper triangle's entry (c, r), transposed, is the lower one's (r, c).
  upper_.resize(matrix.value.size());
  for (size_t p = 0; p < matrix.value.size(); ++p) upper_[p] = matrix.value[p];
  // K(a, b) += u_a v_b, into the block of the equations' nodes: the lower triangle's entry,
  // the diagonal block (whole), or the upper triangle's, held transposed at its lower partner.
  // The blocks each term meets are found first, in parallel (TermPlan); the terms are then
  // added in their order, the blocks of a term a few ahead asked for (they are scattered).
  if (term_plans_.size() < rank_one.size()) term_plans_.resize(rank_one.size());
  std::atomic<bool> outside{false};
  util::parallel_for_static(size_t{0}, rank_one.size(), rank_one.size() >= 256, [&](size_t t) {
    if (!plan_term(matrix, rank_one[t], term_plans_[t])) outside = true;
  });
  if (outside) return false;
  constexpr size_t prefetch_distance = 4;
  for (size_t t = 0; t < rank_one.size(); ++t) {
    if (t + prefetch_distance < rank_one.size())
      for (const int p : term_plans_[t + prefetch_distance].blocks) {
        const char* block = reinterpret_cast<const char*>(matrix.value.data() + p);
        __builtin_prefetch(block, 1), __builtin_prefetch(block + 64, 1);
        const char* other = reinterpret_cast<const char*>(upper_.data() + p);
        __builtin_prefetch(other, 1), __builtin_prefetch(other + 64, 1);
      }
    add_term(matrix, rank_one[t], term_plans_[t]);
  }
  block_lu_ = true;
  return block_lu_factor_.factorize(matrix, upper_);
}

bool LinearSolver::factorize_general(const BlockMatrix& matrix, const std::vector<RankOne>& rank_one) {
  const assembly::DofMap& dofs = *dofs_;
  std::vector<Eigen::Triplet<double>> entries;
  size_t rank_one_entries = 0;
  for (const RankOne& t : rank_one) rank_one_entries += 9 * static_cast<size_t>(t.size());
  entries.reserve(2 * 9 * matrix.value.size() + rank_one_entries);
  auto equation = [&](int block, int d) { return dofs.equation(dofs_per_node * dofs.block_node(block) + d); };
  for (int c = 0; c < matrix.size; ++c) {
    for (int p = matrix.column[c]; p < matrix.column[c + 1]; ++p) {
      if (matrix.is_fill(p)) continue;  // no entry of the tangent (its value is stale)
      const int r = matrix.row[p];
      const linalg::Block& b = matrix.value[p];
      for (int a = 0; a < dofs_per_node; ++a) {
        const int row = equation(r, a);
        if (row < 0) continue;
        for (int d = 0; d < dofs_per_node; ++d) {
          const int col = equation(c, d);
          if (col < 0) continue;
          entries.emplace_back(row, col, b(a, d));
          if (r != c) entries.emplace_back(col, row, b(a, d));
        }
      }
    }
  }
  // Only u vᵀ's nonzero products: a point's v = ∂α/∂x lives on its element's two nodes and its
  // own (9 entries) while u spans every point of the element, so a k-point element's terms are
  // mostly zero (their places are in the block pattern anyway).
  std::vector<int> nonzero_v;
  for (const RankOne& t : rank_one) {
    nonzero_v.clear();
    for (int b = 0; b < t.size(); ++b)
      if (t.equation[b] >= 0 && t.v[b] != 0.0) nonzero_v.push_back(b);
    for (int a = 0; a < t.size(); ++a) {
      if (t.equation[a] < 0 || t.u[a] == 0.0) continue;
      for (const int b : nonzero_v) entries.emplace_back(t.equation[a], t.equation[b], t.u[a] * t.v[b]);
    }
  }
  const int n = dofs.free_count();
  general_matrix_.resize(n, n);
  general_matrix_.setFromTriplets(entries.begin(), entries.end());
  if (!general_matrix_.coeffs().allFinite()) return false;
  lu_ = std::make_unique<Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>>>();
  lu_->analyzePattern(general_matrix_);
  lu_->factorize(general_matrix_);
  return lu_->info() == Eigen::Success;
}

Eigen::VectorXd LinearSolver::solve(const Eigen::VectorXd& rhs) const {
  Eigen::VectorXd x = rhs;
  solve_in_place(x);
  return x;
}

void LinearSolver::solve_in_place(Eigen::VectorXd& x) const {
  if (block_lu_) {
    in_blocks(x, [&](Eigen::VectorXd& b) { block_lu_factor_.solve_in_place(b); });
    return;
  }
  if (general_) {
    const Eigen::VectorXd rhs = x;
    x = lu_->solve(rhs);
    return;
  }
  solve_symmetric_in_place(x);
  if (woodbury_z_.cols() == 0) return;
  // (A + U Vᵀ)⁻¹ b = y − Z (I + Vᵀ Z)⁻¹ Vᵀ y,  y = A⁻¹ b,  Z = A⁻¹ U
  const Eigen::VectorXd w = woodbury_capacitance_.solve(woodbury_v_.transpose() * x);
  x.noalias() -= woodbury_z_ * w;
}

void LinearSolver::solve_symmetric_in_place(Eigen::VectorXd& x) const {
  in_blocks(x, [&](Eigen::VectorXd& b) { ldlt_.solve_in_place(b); });
}

template <class Solve>
void LinearSolver::in_blocks(Eigen::VectorXd& x, const Solve& solve) const {
  if (!padding_needed_) {  // every block is a whole node: the equations are the padded places
    solve(x);
    return;
  }
  padded_work_.setZero(padded_size_);  // constrained dofs of a block carry 0 (no allocation after the first)
  for (Eigen::Index eq = 0; eq < x.size(); ++eq) padded_work_[padded_[eq]] = x[eq];
  solve(padded_work_);
  for (Eigen::Index eq = 0; eq < x.size(); ++eq) x[eq] = padded_work_[padded_[eq]];
}

}  // namespace tsm::solver
