// The assembly after a change of the contact set (GlobalSystem::evaluate_contact_change): only
// the elements at the contacts' nodes are evaluated again, and what they form must be bit for
// bit what a full evaluation forms — forces, tangent, prescribed coupling, rotations, the
// contacts' own results and sliding terms — through activation, hand-over, a second contact,
// release, a contact at a supported node and a contact node no element joins.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <ostream>
#include <utility>
#include <vector>

#include "support/models.hpp"
#include "tsmframe/assembly/global_system.hpp"
#include "tsmframe/contact/contact_set.hpp"

namespace {

using namespace tsm::test;

std::uint64_t bits(double x) { return std::bit_cast<std::uint64_t>(x); }

void expect_same_bits(const Eigen::VectorXd& a, const Eigen::VectorXd& b, const char* what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (Eigen::Index k = 0; k < a.size(); ++k) EXPECT_EQ(bits(a[k]), bits(b[k])) << what << " " << k;
}

void expect_same_evaluation(const tsm::assembly::GlobalSystem& patched, const tsm::assembly::Evaluation& p,
                            const tsm::assembly::GlobalSystem& full, const tsm::assembly::Evaluation& f) {
  expect_same_bits(p.internal_force, f.internal_force, "internal force");
  expect_same_bits(p.prescribed_coupling, f.prescribed_coupling, "prescribed coupling");
  ASSERT_EQ(p.chord_rotations.size(), f.chord_rotations.size());
  for (size_t k = 0; k < p.chord_rotations.size(); ++k) EXPECT_EQ(bits(p.chord_rotations[k]), bits(f.chord_rotations[k])) << k;
  EXPECT_EQ(bits(p.largest_end_rotation), bits(f.largest_end_rotation));
  ASSERT_EQ(p.contacts.size(), f.contacts.size());
  for (size_t k = 0; k < p.contacts.size(); ++k) {
    EXPECT_EQ(bits(p.contacts[k].alpha), bits(f.contacts[k].alpha));
    EXPECT_EQ(bits(p.contacts[k].Y), bits(f.contacts[k].Y));
  }
  const tsm::linalg::BlockMatrix& a = patched.tangent();
  const tsm::linalg::BlockMatrix& b = full.tangent();
  ASSERT_EQ(a.row, b.row) << "both have seen the same contacts: the same pattern";
  for (size_t e = 0; e < a.value.size(); ++e) {
    if (a.is_fill(e)) continue;  // the factorisation's to fill
    for (int k = 0; k < 9; ++k) EXPECT_EQ(bits(a.value[e].data()[k]), bits(b.value[e].data()[k])) << "entry " << e;
  }
  ASSERT_EQ(patched.contact_rank_one().size(), full.contact_rank_one().size());
  for (size_t k = 0; k < full.contact_rank_one().size(); ++k) {
    EXPECT_EQ(patched.contact_rank_one()[k].equation, full.contact_rank_one()[k].equation);
    expect_same_bits(patched.contact_rank_one()[k].u, full.contact_rank_one()[k].u, "sliding u");
    expect_same_bits(patched.contact_rank_one()[k].v, full.contact_rank_one()[k].v, "sliding v");
  }
  expect_same_bits(p.reference_load, f.reference_load, "reference load (follower loads)");
  ASSERT_EQ(patched.follower_rank_one().size(), full.follower_rank_one().size());
  for (size_t k = 0; k < full.follower_rank_one().size(); ++k) {
    expect_same_bits(patched.follower_rank_one()[k].u, full.follower_rank_one()[k].u, "follower u");
    expect_same_bits(patched.follower_rank_one()[k].v, full.follower_rank_one()[k].v, "follower v");
  }
}

// With a follower load (a pressure on the beam) too: its coupling blocks join the elements
// formed again; its skew terms stay. Without a prescribed displacement the contacts' responses
// are kept from one evaluation to the next (KeptPointResponse): a contact that stays where it
// was is not formed again, one that changed element is.
struct Change {
  double pressure = 0.0;
  bool prescribed = true;
};
void PrintTo(const Change& c, std::ostream* os) { *os << "pressure " << c.pressure << (c.prescribed ? ", a prescribed move" : ""); }
class ContactChange : public ::testing::TestWithParam<Change> {};

TEST_P(ContactChange, FormsBitForBitWhatAFullEvaluationForms) {
  // A clamped beam of 6 elements; node 100, the free bottom of a post clamped at its top (all its
  // dofs unknowns); node 200, a pusher no element joins (x and rotation fixed, y prescribed).
  BeamSpec b;
  b.divisions = 6;
  b.A = 1e3;
  b.element = "timoshenko";
  json m = beam_model(b);
  if (GetParam().pressure != 0.0) m["members"][0]["load"] = {{"pressure", GetParam().pressure}};
  m["nodes"].push_back({{"id", 100}, {"x", 0.45}, {"y", 0.0}});
  m["nodes"].push_back({{"id", 11}, {"x", 0.45}, {"y", 0.5}});
  m["nodes"].push_back({{"id", 200}, {"x", 0.75}, {"y", -0.1}});
  m["members"].push_back({{"from", 11}, {"to", 100}, {"divisions", 2}, {"material", "m"}, {"section", "s"}});
  m["supports"] = json::array({{{"node", 1}, {"type", "fixed"}}, {{"node", 11}, {"type", "fixed"}},
                               {{"node", 200}, {"fix", {"ux", "rz"}}}});
  if (GetParam().prescribed) m["prescribed"] = json::array({{{"node", 200}, {"uy", 0.2}}});
  else m["supports"][2]["fix"] = {"ux", "uy", "rz"};  // held where D puts it
  m["contacts"] = json::array({{{"node", 100}, {"members", json::array({0})}}, {{"node", 200}, {"members", json::array({0})}}});
  const tsm::Model model = tsm::io::read_model(m);
  const tsm::assembly::DofMap dofs(model);
  tsm::assembly::GlobalSystem patched(model, dofs), full(model, dofs);
  patched.set_load_factor(0.6);
  full.set_load_factor(0.6);
  const tsm::contact::ContactSet tracker(model);
  std::vector<tsm::contact::ContactState> states = tracker.initial_states();

  // A bent, turned state; the contact nodes near the beam.
  Eigen::VectorXd D = Eigen::VectorXd::Zero(model.dof_count());
  for (int k = 0; k < model.node_count(); ++k) {
    const double x = model.nodes[k].position.x();
    D.segment<3>(3 * k) << -0.05 * x * x, 0.3 * x * x, 0.6 * x;
  }
  D.segment<3>(3 * model.node_index(100)) << -0.01, 0.08, 0.2;
  D.segment<3>(3 * model.node_index(200)) << 0.0, 0.2, 0.0;
  D[3 * model.node_index(2) + 2] += 0.4;  // the tip: element 5's end turns most, till it carries a contact
  std::vector<double> rotations(model.elements.size(), 0.0);
  for (size_t k = 0; k < rotations.size(); ++k) rotations[k] = 0.01 * static_cast<double>(k);

  // (element of contact 100, element of contact 200), −1: inactive.
  const std::vector<std::pair<int, int>> sets = {{2, -1}, {3, -1}, {3, 4}, {-1, 5}, {0, 5}, {4, 4}, {0, -1}, {-1, -1}, {5, 4}, {4, 4}};
  tsm::assembly::Evaluation p, f;
  patched.evaluate(D, rotations, true, p);
  for (const auto& [on_100, on_200] : sets) {
    states[0].active = on_100 >= 0;
    states[0].element = on_100;
    states[0].side = 1;
    states[1].active = on_200 >= 0;
    states[1].element = on_200;
    states[1].side = -1;
    const std::vector<tsm::contact::ActiveContact> active = tracker.active_contacts(states);
    patched.evaluate_contact_change(D, rotations, p, active);
    full.evaluate(D, rotations, true, f, active);
    SCOPED_TRACE(testing::Message() << "contacts on elements " << on_100 << ", " << on_200);
    expect_same_evaluation(patched, p, full, f);
  }
  // The tangent handed out for factorisation is no longer the evaluation's: all is evaluated again.
  patched.tangent_for_factorisation().value[0].setConstant(7.0);
  states[0].active = false;
  const std::vector<tsm::contact::ActiveContact> active = tracker.active_contacts(states);
  patched.evaluate_contact_change(D, rotations, p, active);
  full.evaluate(D, rotations, true, f, active);
  expect_same_evaluation(patched, p, full, f);
}

INSTANTIATE_TEST_SUITE_P(WithoutAndWithAPressureAndAPrescribedMove, ContactChange,
                         ::testing::Values(Change{0.0, true}, Change{0.3, true}, Change{0.0, false}, Change{0.3, false}));

}  // namespace
