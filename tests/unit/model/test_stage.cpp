// stage_model (model/stage.hpp): what one stage of a staged model runs — its own loads scaled
// by λ, earlier stages' held at the λ they ended at, prescribed dofs held from their stage on,
// absolute targets made increments on where a dof stands, a displacement control's start.
#include <gtest/gtest.h>

#include "tsmframe/model/stage.hpp"

namespace {

tsm::Model two_stage_model() {
  tsm::Model m;
  m.nodes = {{1, {0.0, 0.0}}, {2, {1.0, 0.0}}};
  m.constrained.assign(6, false);
  m.constrained[0] = m.constrained[1] = m.constrained[2] = true;
  m.reference_load = Eigen::VectorXd::Zero(6);
  m.reference_load[4] = -2.0;  // a member's lumped load: the first stage's
  tsm::Stage first, second;
  first.load = Eigen::VectorXd::Zero(6);
  first.load[3] = 5.0;
  first.follower_forces.push_back({1, {0.0, 1.0}});
  first.prescribed.push_back({5, 0.25, false});
  second.prescribed.push_back({5, 0.5, false});  // absolute: to 0.5 from where it stands
  second.prescribed.push_back({3, 0.1, true});   // an increment
  second.control.type = tsm::ControlType::displacement;
  second.control.node = 1;
  second.control.dof = tsm::uy;
  second.control.target = 0.3;
  m.stages = {first, second};
  m.member_extras = {{0.7, 0.0, 0.0}};
  return m;
}

TEST(StageModel, TheFirstStageRunsItsOwnLoadsAndTheMembersFromRest) {
  const tsm::Model m = tsm::stage_model(two_stage_model(), 0, {});
  EXPECT_TRUE(m.stages.empty());
  EXPECT_EQ(m.reference_load[3], 5.0);
  EXPECT_EQ(m.reference_load[4], -2.0);
  EXPECT_EQ(m.dead_load.size(), 0);
  EXPECT_EQ(m.start_displacements.size(), 0);
  EXPECT_EQ(m.prescribed(5), 0.25);
  EXPECT_TRUE(m.constrained[5]);
  EXPECT_FALSE(m.constrained[3]);  // prescribed from stage 2 on only
  EXPECT_EQ(m.member_extras[0].pressure, 0.7);
  ASSERT_EQ(m.follower_forces.size(), 1u);
  EXPECT_FALSE(m.follower_forces[0].dead);
  EXPECT_EQ(m.moved_dofs(), (std::vector<int>{3, 5}));  // every stage reports the same dofs
}

TEST(StageModel, ALaterStageHoldsWhatEarlierOnesAppliedAtTheirFinalLoadFactor) {
  tsm::StageStart start{{0.8}, Eigen::VectorXd::Zero(6)};
  start.displacements[3] = 0.02;
  start.displacements[4] = 0.11;
  start.displacements[5] = 0.2;  // 0.8 × 0.25
  const tsm::Model m = tsm::stage_model(two_stage_model(), 1, start);
  EXPECT_EQ(m.reference_load.lpNorm<Eigen::Infinity>(), 0.0);  // stage 2 adds no load
  ASSERT_EQ(m.dead_load.size(), 6);
  EXPECT_DOUBLE_EQ(m.dead_load[3], 0.8 * 5.0);
  EXPECT_DOUBLE_EQ(m.dead_load[4], 0.8 * -2.0);
  ASSERT_EQ(m.follower_forces.size(), 1u);
  EXPECT_TRUE(m.follower_forces[0].dead);
  EXPECT_DOUBLE_EQ(m.follower_forces[0].force.y(), 0.8);
  EXPECT_EQ(m.member_extras[0].pressure, 0.0);
  EXPECT_DOUBLE_EQ(m.member_extras[0].dead_pressure, 0.8 * 0.7);
  EXPECT_TRUE(m.constrained[3] && m.constrained[5]);
  EXPECT_DOUBLE_EQ(m.prescribed(5), 0.5 - 0.2);  // absolute target
  EXPECT_DOUBLE_EQ(m.prescribed(3), 0.1);        // increment
  EXPECT_DOUBLE_EQ(m.prescribed_at(5, 0.0), 0.2);
  EXPECT_DOUBLE_EQ(m.prescribed_at(5, 1.0), 0.5);
  EXPECT_DOUBLE_EQ(m.prescribed_at(0, 0.7), 0.0);  // a support stays put
  EXPECT_DOUBLE_EQ(m.analysis.control.start, 0.11);
  EXPECT_EQ(m.moved_dofs(), (std::vector<int>{3, 5}));
}

}  // namespace
