// What the supports do to the global system after the loop: a skew roller's node turned into
// its frame (t, n), then every held dof's row and column masked (GlobalSystem's).

#include "tsmframe/assembly/global_system.hpp"

namespace tsm::assembly {

void GlobalSystem::turn_to_nodal_frames(Evaluation& out, bool with_tangent) {
  frames_.to_nodal(out.internal_force);
  // The loads no follower load turned in this evaluation are the model's, global: the evaluation
  // carries them turned, copied afresh each time (turning the last evaluation's again would turn twice).
  if (follower_loads_.empty()) out.reference_load = model_.reference_load;
  if (out.reference_load.size() == 0) out.reference_load.setZero(model_.dof_count());
  frames_.to_nodal(out.reference_load);
  if (!follower_loads_.has_dead()) out.dead_load = model_.dead_load;  // empty where none
  if (out.dead_load.size() > 0) frames_.to_nodal(out.dead_load);
  if (!with_tangent) return;
  if (turned_version_ != pattern_version_) {  // the entries in a turned node's row or column, once per pattern
    turned_entries_.clear();
    for (int c = 0; c < tangent_.size; ++c)
      for (int p = tangent_.column[c]; p < tangent_.column[c + 1]; ++p)
        if (frames_.turned(dofs_.block_node(tangent_.row[p])) || frames_.turned(dofs_.block_node(c)))
          turned_entries_.push_back({p, c});
    turned_version_ = pattern_version_;
  }
  for (const auto& [p, c] : turned_entries_)  // the lower triangle's entry (r, c) is K(node r, node c)
    tangent_.value[p] = frames_.to_nodal(dofs_.block_node(tangent_.row[p]), dofs_.block_node(c), tangent_.value[p]);
}

void GlobalSystem::mask_constrained_dofs() {
  // The entries that touch a constrained dof are few (supports): listed once per pattern.
  if (masked_version_ != pattern_version_) {
    masked_entries_.clear();
    for (int c = 0; c < tangent_.size; ++c)
      for (int p = tangent_.column[c]; p < tangent_.column[c + 1]; ++p)
        if ((block_mask_[tangent_.row[p]] | block_mask_[c]) != 0) masked_entries_.push_back({p, c});
    masked_version_ = pattern_version_;
  }
  for (const auto& [p, c] : masked_entries_) {
    const int r = tangent_.row[p];
    const unsigned row_mask = block_mask_[r], column_mask = block_mask_[c];
    linalg::Block& b = tangent_.value[p];
    for (int d = 0; d < dofs_per_node; ++d) {
      if (row_mask >> d & 1u) b.row(d).setZero();
      if (column_mask >> d & 1u) b.col(d).setZero();
    }
    if (r == c)
      for (int d = 0; d < dofs_per_node; ++d)
        if (row_mask >> d & 1u) b(d, d) = 1.0;
  }
}

}  // namespace tsm::assembly
