#pragma once
// A contact that already touches in the model as drawn: its node lies off a candidate element's
// chord by no more than the contact's gap (within rounding), with 0 ≤ α ≤ 1 — a beam resting on a
// knife edge drawn at half its depth (the gap) below it. Such a contact is active from the start
// and holds the structure in the direction normal to the element there (the mechanism check
// counts it), so a beam held only by its contacts can be solved. A node on the centre line itself
// (distance 0) has no side yet — it pushes the way it first moves — and rests on nothing.

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "tsmframe/model/model.hpp"
#include "tsmframe/util/segment_grid.hpp"

namespace tsm {

struct RestingContact {
  int element = -1;          ///< the element it rests on
  double alpha = 0.0;        ///< α = l_ic / l along that element's chord
  int side = 0;              ///< side of the chord the node is on: +1 along n (e turned +90°), −1 against
  Eigen::Vector2d point;     ///< the touch point on the chord
  Eigen::Vector2d normal;    ///< n of that chord (unit)
};

/// The element `contact` rests on in the undeformed model (the nearest, if several), or none.
std::optional<RestingContact> resting_contact(const Model& model, const ContactSpec& contact);
/// resting_contact of every contact of the model (model order), in time linear in the model
/// (the elements near each node, from a grid over the chords).
std::vector<std::optional<RestingContact>> resting_contacts(const Model& model);
/// The same, `chords` the grid drawn_chords gives.
std::vector<std::optional<RestingContact>> resting_contacts(const Model& model, const util::SegmentGrid& chords);
/// A grid over every element's chord as drawn (element indices).
util::SegmentGrid drawn_chords(const Model& model);

}  // namespace tsm
