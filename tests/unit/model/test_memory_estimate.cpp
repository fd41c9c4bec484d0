// A run's memory estimate (model/memory_estimate) against hand counts: the parts a model's
// counts make, the steps and kept states a control and an output selection plan, and the counts
// of a meshed model. (The costs per item are measured against runs: bench/README.md.)
#include "tsmframe/model/memory_estimate.hpp"

#include <gtest/gtest.h>

#include "tsmframe/model/mesh.hpp"

namespace {

using tsm::ModelCounts;
using tsm::estimate_memory;

TEST(MemoryEstimate, AChainWithoutContactsHandCounted) {
  ModelCounts c;
  c.nodes = 101;
  c.elements = 100;
  c.free_dofs = 300;
  c.steps = 10;
  c.kept_states = 1;
  c.monitored = 1;
  c.input_bytes = 1000;
  const tsm::MemoryEstimate e = estimate_memory(c);
  EXPECT_DOUBLE_EQ(e.program.bytes, 6e6);
  EXPECT_DOUBLE_EQ(e.input.bytes, 10 * 1000);                  // the text and its document
  EXPECT_DOUBLE_EQ(e.elements.bytes, 326 * 100 + 152 * 101);    // 47,952
  EXPECT_DOUBLE_EQ(e.kept_states.bytes, 48 * 101 + 32 * 100);  // displacements, reactions; element forces, chord rotations
  EXPECT_DOUBLE_EQ(e.steps.bytes, 10 * (400 + 24 * 1));        // a record each, a monitored node's (u, v, θ)
  EXPECT_DOUBLE_EQ(e.contacts.bytes, 0.0);
  EXPECT_DOUBLE_EQ(e.total(), 6e6 + 10'000 + 47'952 + 8'048 + 4'240);
  EXPECT_EQ(e.elements.name, "100 elements and 101 nodes");
  EXPECT_EQ(e.kept_states.name, "the state of 1 step");
  EXPECT_EQ(e.steps.name, "10 steps' records");
}

TEST(MemoryEstimate, ContactsGrowWithTheirCandidatesAndTheirGroupsTablesWithTheModelsElements) {
  ModelCounts c;
  c.nodes = 103;
  c.elements = 100;
  c.free_dofs = 306;
  c.contacts = 2;
  c.contact_candidates = 2 * 50;
  c.candidate_tables = 1;  // both may touch the same 50 elements
  c.table_candidates = 50;
  c.contact_spec_bytes = 300;
  c.max_iterations = 50;
  // Per contact 900, its kept response (784) and a point per iterate (51), a quarter byte per
  // candidate (a side) and, for up to 64 contacts let go off a free end, 16 per candidate (its
  // place); the group's table: an int per element of the model and 12 per candidate; the
  // settings as read; two dense columns of the tangent (Woodbury); the chords once, and the state
  // the references were taken at, twice.
  EXPECT_DOUBLE_EQ(estimate_memory(c).contacts.bytes, 2 * (900 + 784 + 48 * 51) + 0.25 * 100 + 16 * 100 + (4 * 100 + 12 * 50) +
                                                          300 + 8 * 2 * 306 + 64 * 100 + 48 * 103);
  EXPECT_EQ(estimate_memory(c).contacts.name, "2 contacts with 100 candidate elements");
  // Beyond 32 contacts a sparse LU of the tangent (5 kB per unknown), and the look-ahead's G.
  c.contacts = 40;
  c.contact_candidates = 40 * 100;
  c.table_candidates = 100;
  c.contact_spec_bytes = 0;
  EXPECT_DOUBLE_EQ(estimate_memory(c).contacts.bytes, 40 * (900 + 784 + 48 * 51) + 0.25 * 4000 + 16 * 4000 +
                                                          (4 * 100 + 12 * 100) + 5000 * 306 + 8 * 40 * 40 + 64 * 100 + 48 * 103);
  // The look-ahead takes at most 2,000 contacts in touch; a table per group.
  c.contacts = 20'001;
  c.contact_candidates = 20'001.0 * 20'000;
  c.elements = 20'000;
  c.candidate_tables = 3;
  c.table_candidates = 3 * 20'000;
  const double per_contact = 900 + 784 + 48 * 51;
  EXPECT_DOUBLE_EQ(estimate_memory(c).contacts.bytes, 20'001 * per_contact + 0.25 * 20'001.0 * 20'000 +
                                                          16 * 64 * 20'000.0 + 3 * (4 * 20'000 + 12 * 20'000) +
                                                          5000 * 306 + 8 * 2000.0 * 2000 + 64 * 20'000 + 48 * 103);
  EXPECT_EQ(estimate_memory(c).contacts.name, "20,001 contacts with 400,020,000 candidate elements");
}

TEST(MemoryEstimate, PartsComeLargestFirstWithoutTheEmptyOnes) {
  ModelCounts c;
  c.nodes = 1e6;
  c.elements = 1e6;
  c.kept_states = 100;
  const std::vector<tsm::MemoryPart> parts = estimate_memory(c).parts();
  ASSERT_EQ(parts.size(), 3u);  // no input, contacts or steps
  EXPECT_EQ(parts[0].name, "the state of 100 steps");
  EXPECT_EQ(parts[1].name, "1,000,000 elements and 1,000,000 nodes");
  EXPECT_EQ(parts[2].name, "the program");
}

TEST(MemoryEstimate, StepsPlannedAndStatesKept) {
  tsm::Control load;
  load.steps = 5;
  EXPECT_EQ(tsm::planned_steps(load), 5);
  load.path = {1.0, 0.0, 1.0};  // three legs of 5 steps
  EXPECT_EQ(tsm::planned_steps(load), 15);
  tsm::Control arc;
  arc.type = tsm::ControlType::arc_length;
  arc.max_steps = 700;  // a bound: the most it may take
  EXPECT_EQ(tsm::planned_steps(arc), 700);

  tsm::OutputSelection output;
  EXPECT_EQ(tsm::kept_state_count(output, 10), 10);  // all
  output.kind = tsm::OutputSelection::Kind::last;
  EXPECT_EQ(tsm::kept_state_count(output, 10), 1);
  output.kind = tsm::OutputSelection::Kind::every;
  output.every = 3;
  EXPECT_EQ(tsm::kept_state_count(output, 10), 5);  // steps 3, 6, 9 and the newest, 10: ⌈10/3⌉ + 1
  output.every = 20;
  EXPECT_EQ(tsm::kept_state_count(output, 10), 2);
}

TEST(MemoryEstimate, AMeshedModelsCounts) {
  // Two members of 4 and 6 elements, a contact node that may touch the second.
  tsm::Model model;
  model.nodes = {{1, {0, 0}}, {2, {4, 0}}, {3, {4, 3}}, {9, {2, 1}}};
  model.size = 5.0;
  tsm::MemberMesh mesh(model);
  tsm::MemberInput member;
  member.section = {1.0, 1.0, 0.0};
  member.from = 0, member.to = 1, member.divisions = 4;
  mesh.add(member);
  member.from = 1, member.to = 2, member.divisions = 6;
  mesh.add(member);
  mesh.finish();
  model.constrained[0] = model.constrained[1] = model.constrained[2] = true;
  tsm::ContactSpec contact;
  contact.node = 3;
  contact.members = {1};
  model.contacts = {contact};
  model.analysis.control.steps = 8;
  model.analysis.output.kind = tsm::OutputSelection::Kind::last;
  model.analysis.monitor = {1, 2};

  EXPECT_EQ(tsm::member_element_counts(model), (std::vector<long>{4, 6}));
  const ModelCounts c = tsm::model_counts(model, 123.0);
  EXPECT_EQ(c.input_bytes, 123.0);
  EXPECT_EQ(c.nodes, 4 + 3 + 5);
  EXPECT_EQ(c.elements, 10);
  EXPECT_EQ(c.free_dofs, 3 * 12 - 3);
  EXPECT_EQ(c.contacts, 1);
  EXPECT_EQ(c.contact_candidates, 6);
  EXPECT_EQ(c.candidate_tables, 1);
  EXPECT_EQ(c.table_candidates, 6);
  EXPECT_EQ(c.contact_spec_bytes, sizeof(tsm::ContactSpec) + 4 * model.contacts[0].members.capacity());
  EXPECT_EQ(c.steps, 8);
  EXPECT_EQ(c.kept_states, 1);
  EXPECT_EQ(c.monitored, 2);
  EXPECT_EQ(c.moved_dofs, 0);
}

}  // namespace
