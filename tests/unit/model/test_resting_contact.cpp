// Contacts resting as drawn (model/resting_contact.hpp): all of a model's found at once from a
// grid over the chords are what looking at every element for each contact finds — on a beam
// winding over a plane, with contact nodes at the gap, on the centre line, beyond the gap,
// beyond the beam's ends and between two of its elements.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <random>
#include <vector>

#include "tsmframe/model/resting_contact.hpp"

namespace {

using tsm::Model;

/// A beam of `n` elements (member 0) winding along x, and `contacts` free nodes about it, each a
/// contact node with gap 0.05 that may touch the beam: most placed at the gap off an element
/// (on either side), some on the centre line, some beyond the gap, some anywhere.
Model winding_beam_with_contact_nodes(int n, int contacts, std::mt19937& random) {
  Model model;
  std::uniform_real_distribution<double> wiggle(-0.4, 0.4), unit(0.0, 1.0);
  Eigen::Vector2d x(0.0, 0.0);
  for (int k = 0; k <= n; ++k) {
    model.nodes.push_back({k + 1, x});
    x += Eigen::Vector2d(0.5 + 0.3 * unit(random), wiggle(random));
  }
  for (int k = 0; k < n; ++k) {
    tsm::Element e;
    e.id = k + 1;
    e.start = k;
    e.end = k + 1;
    e.member = 0;
    model.elements.push_back(e);
  }
  const double gap = 0.05;
  for (int c = 0; c < contacts; ++c) {
    const int f = static_cast<int>(unit(random) * n) % n;
    const Eigen::Vector2d a = model.nodes[f].position, b = model.nodes[f + 1].position;
    const Eigen::Vector2d t = (b - a).normalized(), normal(-t.y(), t.x());
    const double alpha = c % 7 == 0 ? (c % 2 ? 0.0 : 1.0) : unit(random), side = c % 2 ? 1.0 : -1.0;
    const double off = c % 5 == 0 ? 0.0 : (c % 11 == 0 ? 2.0 * gap : gap * (1.0 - 1e-12));
    Eigen::Vector2d at = a + alpha * (b - a) + side * off * normal;
    if (c % 13 == 0) at = Eigen::Vector2d(unit(random) * n * 0.65, wiggle(random));
    model.nodes.push_back({static_cast<int>(model.nodes.size()) + 1, at});
    tsm::ContactSpec spec;
    spec.node = static_cast<int>(model.nodes.size()) - 1;
    spec.members = {0};
    spec.gap = gap;
    model.contacts.push_back(spec);
  }
  model.member_count = 1;
  Eigen::Vector2d lo = model.nodes.front().position, hi = lo;
  for (const tsm::Node& node : model.nodes) lo = lo.cwiseMin(node.position), hi = hi.cwiseMax(node.position);
  model.size = (hi - lo).norm();
  model.constrained.assign(tsm::dofs_per_node * model.nodes.size(), false);
  return model;
}

}  // namespace

TEST(RestingContact, AllAtOnceFindsWhatLookingAtEveryElementFinds) {
  std::mt19937 random(3);
  const Model model = winding_beam_with_contact_nodes(400, 600, random);
  const auto all = tsm::resting_contacts(model);
  ASSERT_EQ(all.size(), model.contacts.size());
  int resting = 0;
  for (size_t k = 0; k < model.contacts.size(); ++k) {
    const auto one = tsm::resting_contact(model, model.contacts[k]);
    ASSERT_EQ(all[k].has_value(), one.has_value()) << "contact " << k;
    if (!one) continue;
    ++resting;
    EXPECT_EQ(all[k]->element, one->element) << "contact " << k;
    EXPECT_EQ(all[k]->alpha, one->alpha) << "contact " << k;
    EXPECT_EQ(all[k]->side, one->side) << "contact " << k;
  }
  EXPECT_GT(resting, 300);  // most were drawn at the gap
  EXPECT_LT(resting, 600);  // some on the centre line, beyond the gap or anywhere
}
