#include "tsmframe/model/candidate_groups.hpp"

#include <algorithm>
#include <map>
#include <tuple>

namespace tsm {

CandidateGroups candidate_groups(const std::vector<ContactSpec>& contacts) {
  using Key = std::tuple<std::vector<int>, int, std::vector<double>>;
  std::map<Key, int> groups;
  CandidateGroups g;
  g.of_contact.reserve(contacts.size());
  for (size_t k = 0; k < contacts.size(); ++k) {
    const ContactSpec& c = contacts[k];
    std::vector<int> members = c.members;
    std::sort(members.begin(), members.end());
    members.erase(std::unique(members.begin(), members.end()), members.end());
    const int theory = c.theory ? static_cast<int>(*c.theory) : -1;
    const auto [at, added] =
        groups.try_emplace(Key{std::move(members), theory, c.member_shear_flexibility}, static_cast<int>(g.first.size()));
    if (added) g.first.push_back(static_cast<int>(k));
    g.of_contact.push_back(at->second);
  }
  return g;
}

}  // namespace tsm
