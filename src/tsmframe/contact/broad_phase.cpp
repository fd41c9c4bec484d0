#include "tsmframe/contact/broad_phase.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <utility>

#include "tsmframe/element/chord.hpp"
#include "tsmframe/util/fnv.hpp"

namespace tsm::contact {
namespace {

/// How far the node and the candidates may move in a step with the list still holding: eight
/// elements' lengths (a step along a beam of a few elements keeps its list).
constexpr double allowance_in_elements = 8.0;

}  // namespace

std::uint64_t displacement_stamp(const Eigen::VectorXd& D) {
  std::uint64_t hash = util::fnv_offset;  // FNV-1a over the values' bits
  for (Eigen::Index i = 0; i < D.size(); ++i) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &D[i], sizeof bits);
    hash = util::fnv1a(hash, bits);
  }
  return hash;
}

StepStart step_start(Eigen::VectorXd D, std::vector<double> rotations) {
  const std::uint64_t stamp = displacement_stamp(D);
  return {std::move(D), stamp, std::move(rotations)};
}

StepStart unloaded_start(const Model& model) {
  return step_start(Eigen::VectorXd::Zero(model.dof_count()), std::vector<double>(model.elements.size(), 0.0));
}

namespace {

std::vector<util::Segment> candidate_chords(const ContactGeometry& geometry, const Eigen::VectorXd& D) {
  std::vector<util::Segment> chords;
  chords.reserve(geometry.candidate_elements().size());
  for (const int f : geometry.candidate_elements()) {
    const Element& e = geometry.model().elements[f];
    chords.push_back({geometry.position(e.start, D), geometry.position(e.end, D)});
  }
  return chords;
}

}  // namespace

CandidateChords::CandidateChords(const ContactGeometry& geometry, const Eigen::VectorXd& D)
    : elements_(geometry.candidate_elements()), grid_(candidate_chords(geometry, D)) {}

void CandidateChords::near(const Eigen::Vector2d& x, double radius, std::vector<int>& elements) const {
  grid_.near(x, radius, elements);
  for (int& s : elements) s = elements_[s];
}

void list_near_candidates(const ContactGeometry& geometry, const ContactCandidates& contact, const Eigen::VectorXd& D,
                          std::uint64_t stamp, const CandidateChords& chords, ContactReference& reference) {
  const Model& model = geometry.model();
  // The longest candidate as drawn bounds how far an element's deflected centre line (what the
  // gap is measured from) strays from its chord while its ends turn less than π against it (the
  // cubic's largest offset is 4/27 l (|θ_i| + |θ_j|)).
  const double longest = contact.longest_candidate;
  reference.allowance = allowance_in_elements * longest;
  const double radius = contact.gap + longest + reference.allowance;
  const Eigen::Vector2d node = geometry.position(contact.node, D);
  // The grid's square a little wider than the radius: an element whose distance rounds to the
  // radius is in it.
  std::vector<int> elements;
  chords.near(node, radius * (1.0 + 1e-9) + 1e-12 * node.cwiseAbs().maxCoeff(), elements);
  reference.near.clear();
  for (const int f : elements) {  // ascending, as the candidates
    const int ci = contact.candidate_index[f];
    const Element& e = model.elements[f];
    if (ci >= 0 && element::distance_to_segment(geometry.position(e.start, D), geometry.position(e.end, D), node) <= radius)
      reference.near.push_back(ci);
  }
  reference.near.shrink_to_fit();
  reference.stamp = stamp;
  reference.listed = true;
}

BroadPhase::BroadPhase(const ContactGeometry& geometry, const Eigen::VectorXd& D, const StepStart* start)
    : geometry_(geometry), displacements_(D) {
  if (!start || start->displacements.size() != D.size()) return;
  valid_ = true;
  stamp_ = start->stamp;
  const Eigen::VectorXd& from = start->displacements;
  const Model& model = geometry.model();
  double largest = 0.0;
  for (const int f : geometry.candidate_elements())
    for (const int node : {model.elements[f].start, model.elements[f].end})
      largest = std::max(largest, (D.segment<2>(dofs_per_node * node) - from.segment<2>(dofs_per_node * node)).squaredNorm());
  beam_motion_ = std::sqrt(largest);
}

const std::vector<int>* BroadPhase::candidates(const ContactCandidates& contact, const ContactReference& reference) const {
  if (!valid_ || !reference.listed || reference.stamp != stamp_) return nullptr;
  const Eigen::Vector2d start(reference.position[0], reference.position[1]);
  const double node_motion = (geometry_.position(contact.node, displacements_) - start).norm();
  if (!(node_motion + beam_motion_ < reference.allowance)) return nullptr;  // NaN: all
  return &reference.near;
}

}  // namespace tsm::contact
