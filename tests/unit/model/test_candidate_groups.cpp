// Contacts grouped by what decides their candidates (model/candidate_groups.hpp).
#include <gtest/gtest.h>

#include "tsmframe/model/candidate_groups.hpp"

namespace {

tsm::ContactSpec contact(int node, std::vector<int> members) {
  tsm::ContactSpec c;
  c.node = node;
  c.members = std::move(members);
  return c;
}

TEST(CandidateGroups, ContactsOnTheSameMembersUnderTheSameLawShareOneGroup) {
  std::vector<tsm::ContactSpec> contacts = {contact(0, {1, 2}), contact(1, {2, 1}), contact(2, {1}), contact(3, {1, 2, 2})};
  contacts.push_back(contact(4, {1, 2}));
  contacts.back().theory = tsm::BeamTheory::euler_bernoulli;  // another law on the same members
  contacts.push_back(contact(5, {1, 2}));
  contacts.back().theory = tsm::BeamTheory::timoshenko;
  contacts.back().member_shear_flexibility = {0.0, 1e-3, 1e-3};
  contacts.push_back(contacts.back());
  contacts.back().node = 6;
  contacts.back().member_shear_flexibility = {0.0, 1e-3, 2e-3};  // another Ψ: another law
  const tsm::CandidateGroups groups = tsm::candidate_groups(contacts);
  EXPECT_EQ(groups.of_contact, (std::vector<int>{0, 0, 1, 0, 2, 3, 4}));
  EXPECT_EQ(groups.first, (std::vector<int>{0, 2, 4, 5, 6}));
}

TEST(CandidateGroups, NoContactsNoGroups) {
  const tsm::CandidateGroups groups = tsm::candidate_groups({});
  EXPECT_TRUE(groups.of_contact.empty());
  EXPECT_TRUE(groups.first.empty());
}

}  // namespace
