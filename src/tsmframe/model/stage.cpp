#include "tsmframe/model/stage.hpp"

namespace tsm {

Eigen::VectorXd fixed_load(const Model& model, int t) {
  Eigen::VectorXd load = t == 0 ? model.reference_load : Eigen::VectorXd::Zero(model.dof_count());
  if (model.stages[t].load.size() > 0) load += model.stages[t].load;
  return load;
}

Model stage_model(const Model& model, int stage, const StageStart& start) {
  Model m = model;
  m.stage_moved_dofs = model.moved_dofs();
  m.stages.clear();
  const Stage& s = model.stages[stage];
  const bool at_rest = start.displacements.size() == 0;
  m.reference_load = fixed_load(model, stage);
  m.follower_forces = s.follower_forces;
  Eigen::VectorXd dead = Eigen::VectorXd::Zero(model.dof_count());
  for (int t = 0; t < stage; ++t) {
    const double lambda = start.final_load_factors[t];
    dead += lambda * fixed_load(model, t);
    for (FollowerForce f : model.stages[t].follower_forces) {
      f.force *= lambda;
      f.dead = true;
      m.follower_forces.push_back(f);
    }
  }
  if (stage > 0 && dead.any()) m.dead_load = std::move(dead);
  for (MemberExtras& extras : m.member_extras) {  // the members' pressure is the first stage's
    if (stage == 0) continue;
    extras.dead_pressure = start.final_load_factors[0] * extras.pressure;
    extras.pressure = 0.0;
  }

  m.reference_prescribed = Eigen::VectorXd::Zero(model.dof_count());
  for (int t = 0; t <= stage; ++t)
    for (const PrescribedTarget& p : model.stages[t].prescribed) m.constrained[p.dof] = true;
  for (const PrescribedTarget& p : s.prescribed) {
    const double from = at_rest ? 0.0 : start.displacements[p.dof];
    m.reference_prescribed[p.dof] = p.increment ? p.value : p.value - from;
  }
  if (!m.reference_prescribed.any()) m.reference_prescribed.resize(0);
  if (!at_rest) m.start_displacements = start.displacements;

  for (size_t c = 0; c < s.contact_off.size(); ++c)
    if (s.contact_off[c]) m.contacts[c].members.clear();  // no candidate: never detected
  m.analysis.control = s.control;
  m.analysis.output = s.output;
  Control& control = m.analysis.control;
  if (control.type == ControlType::displacement && !at_rest)
    control.start = start.displacements[dofs_per_node * control.node + control.dof];
  return m;
}

}  // namespace tsm
