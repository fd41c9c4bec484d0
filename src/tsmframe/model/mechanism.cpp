#include "tsmframe/model/mechanism.hpp"

#include "tsmframe/element/chord.hpp"
#include "tsmframe/model/hinges.hpp"
#include "tsmframe/model/nodal_frames.hpp"
#include "tsmframe/model/resting_contact.hpp"

#include <algorithm>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <numeric>
#include <sstream>

namespace tsm {
namespace {

/// Per contact (model order): what it rests on as drawn; empty where resting contacts do not hold.
using RestingAsDrawn = std::vector<std::optional<RestingContact>>;

// Along a free motion the loads do no work to second order where it is below this fraction of
// their scale: round-off and Newton's tolerance leave ~1e-10 of it in a converged state, a load
// that holds or tips a pendulum its whole size.
constexpr double neutral_work = 1e-6;

int find_root(std::vector<int>& parent, int k) {
  while (parent[k] != k) k = parent[k] = parent[parent[k]];
  return k;
}

/// Why a contact from `node`'s side does not rest as drawn, where the reason is plain: its node
/// lies on a candidate element's centre line itself with no gap (no side), or over an element
/// but farther from it than its gap (a part held only by contacts cannot fall onto them), or
/// within its gap of a beam node but beside both elements there — over a corner the beam turns
/// away from, where a point rests on neither element (`corner`). Empty where none holds (the
/// node is beside every candidate element, farther than its gap from their nodes).
std::string why_not_resting(const Model& model, const ContactSpec& contact, bool& corner) {
  const double tolerance = 1e-10 * model.size;
  std::vector<bool> in_set(model.member_count, false);
  for (const int m : contact.members) in_set[m] = true;
  const Eigen::Vector2d x = model.nodes[contact.node].position;
  double nearest = INFINITY, nearest_end = INFINITY;
  int end_node = -1;
  for (const Element& e : model.elements) {
    if (!in_set[e.member] || e.start == contact.node || e.end == contact.node) continue;
    const element::ChordPlace place = element::place_on_chord(model.nodes[e.start].position, model.nodes[e.end].position, x);
    if (place.alpha >= 0.0 && place.alpha <= 1.0) nearest = std::min(nearest, std::abs(place.across));
    for (const int end : {e.start, e.end})
      if (const double d = (model.nodes[end].position - x).norm(); d < nearest_end) nearest_end = d, end_node = end;
  }
  const auto joined = std::count_if(model.elements.begin(), model.elements.end(), [&](const Element& e) {
    return in_set[e.member] && (e.start == end_node || e.end == end_node);
  });
  corner = !(nearest <= contact.gap + tolerance) && nearest_end > tolerance && nearest_end <= contact.gap + tolerance &&
           joined >= 2;  // not a free end
  if (corner) {
    std::ostringstream os;
    os << " (contact node " << model.nodes[contact.node].id << " is drawn " << nearest_end << " from beam node "
       << model.nodes[end_node].id << ", within its gap " << contact.gap
       << ", but beside both elements there: over a corner the beam turns away from, where a point rests on "
          "neither — draw it over an element, at the gap from its chord)";
    return os.str();
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

std::string not_resting(const Model& model, const ContactSpec& contact) {
  bool corner = false;
  return why_not_resting(model, contact, corner);
}

/// The nodes that elements join into connected parts (a union-find over the nodes), and the
/// nodes some element holds; a node no element holds is in no part (unheld_node checks it).
struct Parts {
  std::vector<int> parent;
  std::vector<bool> held;
  std::vector<std::vector<int>> members;  // per root: the part's held nodes, ascending (members_by_root)

  int root(int k) { return find_root(parent, k); }
};

Parts join_by_elements(const Model& model) {
  const int n = model.node_count();
  Parts parts;
  parts.parent.resize(n);
  std::iota(parts.parent.begin(), parts.parent.end(), 0);
  parts.held.assign(n, false);
  for (const Element& e : model.elements) {
    parts.held[e.start] = parts.held[e.end] = true;
    parts.parent[parts.root(e.start)] = parts.root(e.end);
  }
  return parts;
}

void members_by_root(Parts& parts) {
  const int n = static_cast<int>(parts.parent.size());
  parts.members.assign(n, {});
  for (int k = 0; k < n; ++k)
    if (parts.held[k]) parts.members[parts.root(k)].push_back(k);
}

/// Whether the springs at node k hold each dof its supports leave free: the free translations'
/// directions spanned by translation springs, a free rotation by a rotation spring.
bool held_by_springs(const Model& model, const NodalFrames& frames, int k) {
  Eigen::Matrix2d spanned = Eigen::Matrix2d::Zero();
  bool rotation = false, any = false;
  for (const NodalSpring& s : model.springs) {
    if (s.node != k) continue;
    any = true;
    if (s.kind == NodalSpring::Kind::rotation) rotation = true;
    else spanned += s.direction * s.direction.transpose();
  }
  if (!any) return false;
  const Eigen::Matrix3d T = frames.frame(k);  // a skew roller frees its t
  for (const int dof : {ux, uy})
    if (!model.constrained[dofs_per_node * k + dof] && !model.constrained[dofs_per_node * k + 1 - dof] &&
        std::abs(spanned.determinant()) < 1e-12)
      return false;  // both free: the springs must span the plane
    else if (const Eigen::Vector2d axis = T.col(dof).head<2>();
             !model.constrained[dofs_per_node * k + dof] && axis.dot(spanned * axis) < 1e-12)
      return false;
  return rotation || model.constrained[dofs_per_node * k + rz];
}

/// The first node no element holds with a dof its supports leave free, named with that dof, or
/// none. A contact node resting on a beam as drawn is held by it along the normal there: enough
/// if that is its one free translation's direction, in part (a load riding on a beam: ux
/// prescribed, uy free).
std::optional<std::string> unheld_node(const Model& model, const std::vector<bool>& held, const RestingAsDrawn& resting) {
  std::vector<int> contact_of(model.node_count(), -1);  // a look-up, not a search per node
  for (size_t c = 0; c < model.contacts.size(); ++c) contact_of[model.contacts[c].node] = static_cast<int>(c);
  const NodalFrames frames(model);
  for (int k = 0; k < model.node_count(); ++k) {
    if (held[k]) continue;
    const int contact = contact_of[k];
    const bool contact_node = contact >= 0;
    int free_translations = 0, free_dof = -1;
    for (const int dof : {ux, uy})
      if (!model.constrained[dofs_per_node * k + dof]) ++free_translations, free_dof = dof;
    if (held_by_springs(model, frames, k)) continue;
    if (!resting.empty() && contact_node && free_translations == 1 && model.constrained[dofs_per_node * k + rz]) {
      const Eigen::Vector2d free_direction = frames.frame(k).col(free_dof).head<2>();  // x, y or a skew roller's t
      if (const auto& r = resting[contact]; r && std::abs(r->normal.dot(free_direction)) > 1e-6) continue;
    }
    for (int dof = 0; dof < dofs_per_node; ++dof)
      if (!model.constrained[dofs_per_node * k + dof])
        return "structure is a mechanism: node " + std::to_string(model.nodes[k].id) +
               " is held by no element and its " + dof_name(dof) + " is not supported" +
               (contact_node ? std::string(" (a contact node is held by its contact only if drawn at its \"gap\" from the "
                                           "beam and free in one direction only, across the beam: else prescribe its "
                                           "motion, or make it a node of a beam)") +
                                   not_resting(model, model.contacts[contact])
                             : std::string());
  }
  return std::nullopt;
}

/// A contact resting on a part as drawn (resting_contact): its touch point and normal on the
/// element's part, and its node's part (−1: a node held in both translations by supports, in no
/// part).
struct Touch {
  int node_part, element_part;  // roots
  Eigen::Vector2d point, normal;
};

/// The contacts resting as drawn whose node is held, by supports (a knife edge) or as a node of
/// a part; none where `resting` is empty (resting contacts do not hold).
std::vector<Touch> resting_touches(const Model& model, Parts& parts, const RestingAsDrawn& resting) {
  std::vector<Touch> touches;
  for (size_t k = 0; k < resting.size(); ++k) {
    const ContactSpec& c = model.contacts[k];
    const bool fixed = model.constrained[dofs_per_node * c.node + ux] && model.constrained[dofs_per_node * c.node + uy];
    if (!fixed && !parts.held[c.node]) continue;
    if (const auto& r = resting[k])
      touches.push_back({fixed ? -1 : parts.root(c.node), parts.root(model.elements[r->element].start), r->point, r->normal});
  }
  return touches;
}

/// What holds a part beside its supports: a contact resting on it, or a translation spring, along
/// `normal` at `point`; a rotation spring (`rotation`: it holds the part's rotation alone).
struct Restraint {
  Eigen::Vector2d point, normal;
  bool rotation = false;
};
using Resting = std::vector<Restraint>;

/// The part's rigid-body modes against its supports: the Gram matrix of the constraint rows
/// (translation x, y; rotation about the centre, scaled by the part's extent so the columns are
/// commensurate), one row per constrained dof and per contact holding it.
struct Modes {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  Eigen::Vector2d centre;
  double extent = 1.0;
  bool stable() const { return eig.eigenvalues()[0] > 1e-10 * std::max(1.0, eig.eigenvalues()[2]); }
};

/// Where node k stands: as drawn, or displaced by `displacements` (global, every dof).
Eigen::Vector2d position(const Model& model, const Eigen::VectorXd* displacements, int k) {
  const Eigen::Vector2d& drawn = model.nodes[k].position;
  return displacements ? Eigen::Vector2d(drawn + displacements->segment<2>(dofs_per_node * k)) : drawn;
}

Modes modes_of(const Model& model, const NodalFrames& frames, const std::vector<char>& hinge, const std::vector<int>& part,
               const Resting& resting, const Eigen::VectorXd* displacements = nullptr) {
  Modes m;
  m.centre = Eigen::Vector2d::Zero();
  Eigen::Vector2d lo = position(model, displacements, part.front()), hi = lo;
  for (int k : part) {
    const Eigen::Vector2d p = position(model, displacements, k);
    m.centre += p;
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  m.centre /= static_cast<double>(part.size());
  m.extent = std::max((hi - lo).norm(), 1e-300);
  Eigen::Matrix3d gram = Eigen::Matrix3d::Zero();
  for (int k : part) {
    const Eigen::Vector2d p = (position(model, displacements, k) - m.centre) / m.extent;
    // A held translation holds along its frame's axis: x or y, or a skew roller's normal.
    const Eigen::Matrix3d T = frames.frame(k);
    const auto held = [&](int d) { return Eigen::Vector3d(T(0, d), T(1, d), -T(0, d) * p.y() + T(1, d) * p.x()); };
    const Eigen::Vector3d rows[3] = {held(ux), held(uy), {0.0, 0.0, 1.0}};
    // A fixed rotation where every element end is hinged holds nothing of the part.
    for (int dof = 0; dof < dofs_per_node; ++dof)
      if (model.constrained[dofs_per_node * k + dof] && (dof != rz || !hinge[k])) gram += rows[dof] * rows[dof].transpose();
  }
  for (const Restraint& r : resting) {
    const Eigen::Vector2d p = (r.point - m.centre) / m.extent;
    const Eigen::Vector3d row = r.rotation ? Eigen::Vector3d(0.0, 0.0, 1.0)
                                           : Eigen::Vector3d(r.normal.x(), r.normal.y(), -r.normal.x() * p.y() + r.normal.y() * p.x());
    gram += row * row.transpose();
  }
  m.eig.compute(gram);
  return m;
}

/// Which parts are held, and the contacts holding each (per part root).
struct Holding {
  std::vector<Resting> resting;
  std::vector<char> held;
};

/// Hands each unused touch to the part it holds: the element's part where the node is held, or
/// the other way round the node's part where the element's part is held. True if any was.
bool pass_touches(const std::vector<Touch>& touches, std::vector<char>& used, Holding& holding) {
  bool changed = false;
  for (size_t t = 0; t < touches.size(); ++t) {
    if (used[t]) continue;
    const Touch& touch = touches[t];
    const bool node_held = touch.node_part < 0 || holding.held[touch.node_part];
    if (node_held && touch.node_part != touch.element_part) {
      holding.resting[touch.element_part].push_back({touch.point, touch.normal});
    } else if (holding.held[touch.element_part] && touch.node_part >= 0 && touch.node_part != touch.element_part) {
      holding.resting[touch.node_part].push_back({touch.point, touch.normal});
    } else {
      continue;
    }
    used[t] = 1;
    changed = true;
  }
  return changed;
}

/// A resting contact holds the part it rests on along the element's normal at the touch point
/// where its node is held — in both translations by supports (a knife edge), or as a node of a
/// part that is itself held (a beam lying on a supported one) — and, the other way round, holds
/// its node's part where the part it rests on is held. Bilaterally, for this check: a contact
/// lets go only if it would pull, which a solve finds out. Parts held so hold others in turn,
/// until nothing changes.
Holding hold_parts(const Model& model, const NodalFrames& frames, const std::vector<char>& hinge, Parts& parts,
                   const std::vector<Touch>& touches) {
  const int n = model.node_count();
  Holding holding{std::vector<Resting>(n), std::vector<char>(n, 0)};
  for (const NodalSpring& s : model.springs)  // a spring holds its node's part as a support would
    if (parts.held[s.node] && !(s.kind == NodalSpring::Kind::rotation && hinge[s.node]))
      holding.resting[parts.root(s.node)].push_back(
          {model.nodes[s.node].position, s.direction, s.kind == NodalSpring::Kind::rotation});
  std::vector<char> used(touches.size(), 0);
  for (bool changed = true; changed;) {
    changed = pass_touches(touches, used, holding);
    for (const std::vector<int>& part : parts.members) {
      if (part.empty()) continue;
      const int root = parts.root(part.front());
      if (!holding.held[root] && modes_of(model, frames, hinge, part, holding.resting[root]).stable())
        holding.held[root] = 1, changed = true;
    }
  }
  return holding;
}

/// The free motion of the part's weakest mode (a, b, ω·extent): a translation's direction, or a
/// rotation about its pole.
FreeMotion motion_of(const Modes& m, const std::vector<int>& part) {
  const Eigen::Vector3d mode = m.eig.eigenvectors().col(0);
  FreeMotion motion;
  motion.node = part.front();
  motion.part_nodes = static_cast<int>(part.size());
  if (std::abs(mode[2]) < 1e-6) {
    motion.kind = FreeMotion::Kind::translation;
    motion.direction = mode.head<2>().normalized();
  } else {
    const double omega = mode[2] / m.extent;
    motion.kind = FreeMotion::Kind::rotation;
    motion.pole = m.centre + Eigen::Vector2d(-mode[1] / omega, mode[0] / omega);
    // To a millionth of the part's extent, on a decimal grid: finer digits are round-off (a
    // converged state's pole on its pin reads (0, 0), not (1e-10, -2e-16)).
    const double grid = std::pow(10.0, std::floor(std::log10(m.extent)) - 6.0);
    motion.pole = (motion.pole / grid).array().round().matrix() * grid + Eigen::Vector2d::Zero();
  }
  return motion;
}

/// Whether a contact acts on the part: onto the elements of its members, or from its nodes.
bool contacts_touch_part(const Model& model, Parts& parts, int root) {
  std::vector<bool> contact_member(model.member_count, false);
  for (const ContactSpec& c : model.contacts)
    for (const int m : c.members) contact_member[m] = true;
  return std::any_of(model.elements.begin(), model.elements.end(),
                     [&](const Element& e) { return contact_member[e.member] && parts.root(e.start) == root; }) ||
         std::any_of(model.contacts.begin(), model.contacts.end(),
                     [&](const ContactSpec& c) { return parts.held[c.node] && parts.root(c.node) == root; });
}

/// Why the first contact from the part's nodes, or onto its members, that plainly does not rest
/// does not (why_not_resting); empty if none plainly does not. Each contact looked at weighs its
/// node against every element: past 5·10⁷ such pairs (a fraction of a second) it stops looking —
/// a model of 10⁵ contact nodes on 10⁵ elements took a minute to be told it is a mechanism.
std::string first_not_resting(const Model& model, Parts& parts, int root) {
  std::vector<bool> member_on_part(model.member_count, false);
  for (const Element& e : model.elements)
    if (parts.root(e.start) == root) member_on_part[e.member] = true;
  constexpr double most_pairs = 5e7;
  double pairs = 0.0;
  std::string first;
  for (const ContactSpec& c : model.contacts) {
    const bool on_part = parts.root(c.node) == root ||
                         std::any_of(c.members.begin(), c.members.end(), [&](int m) { return member_on_part[m]; });
    if (!on_part) continue;
    if ((pairs += static_cast<double>(model.elements.size())) > most_pairs) break;
    // A node drawn at a corner is likely the one meant to rest: it goes first.
    bool corner = false;
    std::string why = why_not_resting(model, c, corner);
    if (corner) return why;
    if (first.empty()) first = std::move(why);
  }
  return first;
}

/// The sentence for a part no support holds: its free motion and, where contacts act on it,
/// when a contact holds it. Contacts on this part, or from its nodes, count only where they rest
/// as drawn.
std::string free_part(const Model& model, Parts& parts, const std::vector<int>& part, int root, const Modes& m) {
  const FreeMotion motion = motion_of(m, part);
  std::ostringstream os;
  os << "structure is a mechanism: " << part_text(model, motion) << " is free to " << motion_text(motion);
  if (motion.kind == FreeMotion::Kind::rotation) os << " (add a support that stops it)";
  else if (std::abs(motion.direction.y()) < 1e-9) os << " (no support fixes ux)";
  else if (std::abs(motion.direction.x()) < 1e-9) os << " (no support fixes uy)";
  if (contacts_touch_part(model, parts, root)) {
    os << "; a contact holds it from the start only if its node is drawn at the contact's \"gap\" from the "
          "beam's centre line, on the side it supports, and the node or the beam is held (by supports, or by a "
          "part that is)";
    os << first_not_resting(model, parts, root);
  }
  return os.str();
}

/// find_mechanism; without `explain`, an empty sentence for a part no support holds.
std::optional<std::string> first_mechanism(const Model& model, bool resting_contacts_hold, bool explain) {
  Parts parts = join_by_elements(model);
  const std::vector<char> hinge = hinge_nodes(model);
  const RestingAsDrawn resting = resting_contacts_hold ? resting_contacts(model) : RestingAsDrawn{};
  if (auto message = unheld_node(model, parts.held, resting)) return message;
  members_by_root(parts);
  const std::vector<Touch> touches = resting_touches(model, parts, resting);
  const NodalFrames frames(model);
  const Holding holding = hold_parts(model, frames, hinge, parts, touches);
  for (const std::vector<int>& part : parts.members) {
    if (part.empty()) continue;
    const int root = parts.root(part.front());
    if (holding.held[root]) continue;
    if (!explain) return std::string();
    return free_part(model, parts, part, root, modes_of(model, frames, hinge, part, holding.resting[root]));
  }
  return std::nullopt;
}

}  // namespace

std::optional<std::string> find_mechanism(const Model& model, bool resting_contacts_hold) {
  return first_mechanism(model, resting_contacts_hold, true);
}

bool is_mechanism(const Model& model, bool resting_contacts_hold) {
  return first_mechanism(model, resting_contacts_hold, false).has_value();
}

std::optional<std::string> starting_mechanism(Model& model) {
  if (model.stages.empty()) return find_mechanism(model);
  const std::vector<bool> supports = model.constrained;
  for (const PrescribedTarget& p : model.stages.front().prescribed) model.constrained[p.dof] = true;
  const auto mechanism = find_mechanism(model);
  model.constrained = supports;
  return mechanism;
}

std::string part_text(const Model& model, const FreeMotion& motion) {
  std::ostringstream os;
  os << "the part holding node " << model.nodes[motion.node].id;
  if (motion.part_nodes > 1)
    os << " and the " << motion.part_nodes - 1 << (motion.part_nodes == 2 ? " node" : " nodes") << " joined to it";
  return os.str();
}

std::string motion_text(const FreeMotion& motion) {
  std::ostringstream os;
  if (motion.kind == FreeMotion::Kind::rotation) os << "rotate about (" << motion.pole.x() << ", " << motion.pole.y() << ")";
  else if (std::abs(motion.direction.y()) < 1e-9) os << "move along x";
  else if (std::abs(motion.direction.x()) < 1e-9) os << "move along y";
  else os << "move in the direction " << std::atan2(motion.direction.y(), motion.direction.x()) << " rad from x";
  return os.str();
}

SupportedParts::SupportedParts(const Model& model) : model_(model), frames_(model), hinge_(hinge_nodes(model)) {
  Parts parts = join_by_elements(model);
  members_by_root(parts);
  std::vector<int> index_of(model.node_count(), -1);  // a root's part
  for (std::vector<int>& part : parts.members) {
    if (part.empty()) continue;
    index_of[parts.root(part.front())] = static_cast<int>(parts_.size());
    parts_.push_back(std::move(part));
  }
  springs_.resize(parts_.size());
  for (size_t s = 0; s < model.springs.size(); ++s)
    if (const int node = model.springs[s].node; parts.held[node])
      springs_[index_of[parts.root(node)]].push_back(static_cast<int>(s));
}

std::optional<FreeMotion> SupportedParts::neutral_motion(const Eigen::VectorXd& displacements,
                                                         const Eigen::VectorXd& internal_forces) const {
  for (size_t p = 0; p < parts_.size(); ++p) {
    Resting resting;  // a spring holds its node's part as a support would, where its node stands
    for (const int s : springs_[p])
      if (const NodalSpring& spring = model_.springs[s]; !(spring.kind == NodalSpring::Kind::rotation && hinge_[spring.node]))
        resting.push_back({position(model_, &displacements, spring.node), spring.direction,
                           spring.kind == NodalSpring::Kind::rotation});
    const Modes modes = modes_of(model_, frames_, hinge_, parts_[p], resting, &displacements);
    if (modes.stable()) continue;
    const FreeMotion motion = motion_of(modes, parts_[p]);
    if (motion.kind == FreeMotion::Kind::translation) return motion;  // a translation changes no internal force
    // Turned by φ about the pole, the part's internal forces f_i turn with it: the tangent's
    // second-order work along the motion is Σ r_i · f_i (r_i from the pole), against the
    // moments and forces' own scale Σ (extent |f_i| + |m_i|).
    double work = 0.0, scale = 0.0;
    for (const int k : parts_[p]) {
      const Eigen::Vector2d f = internal_forces.segment<2>(dofs_per_node * k);
      work += (position(model_, &displacements, k) - motion.pole).dot(f);
      scale += modes.extent * f.norm() + std::abs(internal_forces[dofs_per_node * k + rz]);
    }
    if (std::abs(work) <= neutral_work * scale) return motion;
  }
  return std::nullopt;
}

}  // namespace tsm
