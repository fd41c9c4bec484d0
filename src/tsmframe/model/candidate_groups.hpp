#pragma once
// Contacts that may touch the same elements under the same law: the nodes of one contact entry
// (a beam's every node against another beam) share one table of candidate elements, so what the
// tables cost grows with the entries, not with contacts × elements.

#include <vector>

#include "tsmframe/model/model.hpp"

namespace tsm {

struct CandidateGroups {
  std::vector<int> of_contact;  ///< per contact (model order): its group
  std::vector<int> first;       ///< per group: its first contact
};

/// Groups the contacts by what decides their candidates: the members they may touch, the
/// contact law's beam theory and its per-member Ψ.
CandidateGroups candidate_groups(const std::vector<ContactSpec>& contacts);

}  // namespace tsm
