#include "tsmframe/model/mechanism.hpp"

#include "tsmframe/element/chord.hpp"
#include "tsmframe/model/hinges.hpp"
#include "tsmframe/model/resting_contact.hpp"

#include <algorithm>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <numeric>
#include <sstream>

namespace tsm {
namespace {

int find_root(std::vector<int>& parent, int k) {
  while (parent[k] != k) k = parent[k] = parent[parent[k]];
  return k;
}

std::string part_name(const Model& model, const std::vector<int>& members) {
  std::ostringstream os;
  os << "node " << model.nodes[members.front()].id;
  if (members.size() > 1) os << " and the " << members.size() - 1 << " nodes joined to it";
  return os.str();
}

/// Why a contact from `node`'s side does not rest as drawn, where the reason is plain: its node
/// lies on a candidate element's centre line itself with no gap (no side), or over an element
/// but farther from it than its gap (a part held only by contacts cannot fall onto them).
/// Empty where neither holds (the node is beside every candidate element).
std::string why_not_resting(const Model& model, const ContactSpec& contact) {
  const double tolerance = 1e-10 * model.size;
  std::vector<bool> in_set(model.member_count, false);
  for (const int m : contact.members) in_set[m] = true;
  const Eigen::Vector2d x = model.nodes[contact.node].position;
  double nearest = INFINITY;
  for (const Element& e : model.elements) {
    if (!in_set[e.member] || e.start == contact.node || e.end == contact.node) continue;
    const element::ChordPlace place = element::place_on_chord(model.nodes[e.start].position, model.nodes[e.end].position, x);
    if (place.alpha >= 0.0 && place.alpha <= 1.0) nearest = std::min(nearest, std::abs(place.across));
  }
  std::ostringstream os;
  const int id = model.nodes[contact.node].id;
  if (nearest <= tolerance && contact.gap <= tolerance)
    os << " (contact node " << id << " lies on the centre line itself with gap 0, so it rests on neither side: draw it "
       << "at the beam's surface and give that distance as its \"gap\", e.g. half the two depths)";
  else if (std::isfinite(nearest) && nearest > contact.gap + tolerance)
    os << " (contact node " << id << " is drawn " << nearest << " from the beam's centre line, its gap is " << contact.gap
       << ": a part that only contacts would hold cannot fall onto them in a static analysis — draw it touching, at "
       << "the gap, or move it there with a prescribed displacement"
       << (nearest < 1.1 * contact.gap ? "; the distance is to the elements' straight chords, which on an arc lie inside "
                                          "the circle"
                                        : "")
       << ")";
  return os.str();
}

}  // namespace

std::optional<std::string> find_mechanism(const Model& model, bool resting_contacts_hold) {
  const int n = model.node_count();
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  std::vector<bool> held(n, false);
  for (const Element& e : model.elements) {
    held[e.start] = held[e.end] = true;
    parent[find_root(parent, e.start)] = find_root(parent, e.end);
  }
  const std::vector<char> hinge = hinge_nodes(model);
  for (int k = 0; k < n; ++k) {
    if (held[k]) continue;
    const auto spec = std::find_if(model.contacts.begin(), model.contacts.end(), [&](const ContactSpec& c) { return c.node == k; });
    const bool contact_node = spec != model.contacts.end();
    // A contact node resting on a beam as drawn is held by it along the normal there: enough if
    // that is its one free translation's direction, in part (a load riding on a beam: ux
    // prescribed, uy free).
    int free_translations = 0, free_dof = -1;
    for (const int dof : {ux, uy})
      if (!model.constrained[dofs_per_node * k + dof]) ++free_translations, free_dof = dof;
    if (resting_contacts_hold && contact_node && free_translations == 1 && model.constrained[dofs_per_node * k + rz])
      if (const auto r = resting_contact(model, *spec); r && std::abs(r->normal[free_dof]) > 1e-6) continue;
    for (int dof = 0; dof < dofs_per_node; ++dof)
      if (!model.constrained[dofs_per_node * k + dof])
        return "structure is a mechanism: node " + std::to_string(model.nodes[k].id) +
               " is held by no element and its " + dof_name(dof) + " is not supported" +
               (contact_node ? std::string(" (a contact node is held by its contact only if drawn at its \"gap\" from the "
                                           "beam and free in one direction only, across the beam: else prescribe its "
                                           "motion, or make it a node of a beam)") +
                                   why_not_resting(model, *spec)
                             : std::string());
  }
  std::vector<std::vector<int>> parts(n);
  for (int k = 0; k < n; ++k)
    if (held[k]) parts[find_root(parent, k)].push_back(k);
  // A contact resting on a part as drawn (resting_contact) holds that part along the element's
  // normal at the touch point where its node is held — in both translations by supports (a knife
  // edge), or as a node of a part that is itself held (a beam lying on a supported one) — and,
  // the other way round, holds its node's part where the part it rests on is held. Bilaterally,
  // for this check: a contact lets go only if it would pull, which a solve finds out. Parts held
  // so hold others in turn, until nothing changes.
  struct Touch {
    int node_part, element_part;  // roots; node_part −1: a node held by supports, in no part
    Eigen::Vector2d point, normal;
  };
  std::vector<Touch> touches;
  for (const ContactSpec& c : model.contacts) {
    if (!resting_contacts_hold) break;
    const bool fixed = model.constrained[dofs_per_node * c.node + ux] && model.constrained[dofs_per_node * c.node + uy];
    if (!fixed && !held[c.node]) continue;
    if (const auto r = resting_contact(model, c))
      touches.push_back({fixed ? -1 : find_root(parent, c.node), find_root(parent, model.elements[r->element].start),
                         r->point, r->normal});
  }
  std::vector<std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>>> resting(n);  // per part root: (point, normal)
  std::vector<char> part_held(n, 0), used(touches.size(), 0);
  // The part's rigid-body modes against its supports: the Gram matrix of the constraint rows
  // (translation x, y; rotation about the centre, scaled by the part's extent so the columns are
  // commensurate), one row per constrained dof and per contact holding it.
  struct Modes {
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
    Eigen::Vector2d centre;
    double extent = 1.0;
    bool stable() const { return eig.eigenvalues()[0] > 1e-10 * std::max(1.0, eig.eigenvalues()[2]); }
  };
  auto modes_of = [&](const std::vector<int>& part, int root) {
    Modes m;
    m.centre = Eigen::Vector2d::Zero();
    Eigen::Vector2d lo = model.nodes[part.front()].position, hi = lo;
    for (int k : part) {
      const Eigen::Vector2d& p = model.nodes[k].position;
      m.centre += p;
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    m.centre /= static_cast<double>(part.size());
    m.extent = std::max((hi - lo).norm(), 1e-300);
    Eigen::Matrix3d gram = Eigen::Matrix3d::Zero();
    for (int k : part) {
      const Eigen::Vector2d p = (model.nodes[k].position - m.centre) / m.extent;
      const Eigen::Vector3d rows[3] = {{1.0, 0.0, -p.y()}, {0.0, 1.0, p.x()}, {0.0, 0.0, 1.0}};
      // A fixed rotation where every element end is hinged holds nothing of the part.
      for (int dof = 0; dof < dofs_per_node; ++dof)
        if (model.constrained[dofs_per_node * k + dof] && (dof != rz || !hinge[k])) gram += rows[dof] * rows[dof].transpose();
    }
    for (const auto& [point, normal] : resting[root]) {
      const Eigen::Vector2d p = (point - m.centre) / m.extent;
      const Eigen::Vector3d row(normal.x(), normal.y(), -normal.x() * p.y() + normal.y() * p.x());
      gram += row * row.transpose();
    }
    m.eig.compute(gram);
    return m;
  };
  for (bool changed = true; changed;) {
    changed = false;
    for (size_t t = 0; t < touches.size(); ++t) {
      if (used[t]) continue;
      const Touch& touch = touches[t];
      const bool node_held = touch.node_part < 0 || part_held[touch.node_part];
      if (node_held && touch.node_part != touch.element_part) {
        resting[touch.element_part].push_back({touch.point, touch.normal});
      } else if (part_held[touch.element_part] && touch.node_part >= 0 && touch.node_part != touch.element_part) {
        resting[touch.node_part].push_back({touch.point, touch.normal});
      } else {
        continue;
      }
      used[t] = 1;
      changed = true;
    }
    for (const std::vector<int>& part : parts) {
      if (part.empty()) continue;
      const int root = find_root(parent, part.front());
      if (!part_held[root] && modes_of(part, root).stable()) part_held[root] = 1, changed = true;
    }
  }

  for (const std::vector<int>& part : parts) {
    if (part.empty()) continue;
    const int root = find_root(parent, part.front());
    if (part_held[root]) continue;
    const Modes m = modes_of(part, root);
    const Eigen::Vector3d mode = m.eig.eigenvectors().col(0);  // (a, b, ω·extent)
    const double extent = m.extent;
    const Eigen::Vector2d centre = m.centre;
    std::ostringstream os;
    os << "structure is a mechanism: the part holding " << part_name(model, part) << " is free to ";
    if (std::abs(mode[2]) < 1e-6) {
      const double angle = std::atan2(mode[1], mode[0]);
      if (std::abs(mode[1]) < 1e-9) os << "move along x (no support fixes ux)";
      else if (std::abs(mode[0]) < 1e-9) os << "move along y (no support fixes uy)";
      else os << "move in the direction " << angle << " rad from x";
    } else {
      const double omega = mode[2] / extent;
      const Eigen::Vector2d pole = centre + Eigen::Vector2d(-mode[1] / omega, mode[0] / omega);
      os << "rotate about (" << pole.x() << ", " << pole.y() << ") (add a support that stops it)";
    }
    // Contacts on this part, or from its nodes, count only where they rest as drawn.
    std::vector<bool> contact_member(model.member_count, false);
    for (const ContactSpec& c : model.contacts)
      for (const int m : c.members) contact_member[m] = true;
    const bool touches_part =
        std::any_of(model.elements.begin(), model.elements.end(),
                    [&](const Element& e) { return contact_member[e.member] && find_root(parent, e.start) == root; }) ||
        std::any_of(model.contacts.begin(), model.contacts.end(),
                    [&](const ContactSpec& c) { return held[c.node] && find_root(parent, c.node) == root; });
    if (touches_part) {
      os << "; a contact holds it from the start only if its node is drawn at the contact's \"gap\" from the "
            "beam's centre line, on the side it supports, and the node or the beam is held (by supports, or by a "
            "part that is)";
      // The first contact from this part's nodes, or onto its members, that plainly does not rest.
      for (const ContactSpec& c : model.contacts) {
        std::vector<bool> in_set(model.member_count, false);
        for (const int m : c.members) in_set[m] = true;
        const bool on_part = find_root(parent, c.node) == root ||
                             std::any_of(model.elements.begin(), model.elements.end(), [&](const Element& e) {
                               return in_set[e.member] && find_root(parent, e.start) == root;
                             });
        const std::string why = on_part ? why_not_resting(model, c) : std::string();
        if (!why.empty()) {
          os << why;
          break;
        }
      }
    }
    return os.str();
  }
  return std::nullopt;
}

}  // namespace tsm
