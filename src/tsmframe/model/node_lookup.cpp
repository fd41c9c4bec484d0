#include "tsmframe/model/node_lookup.hpp"

#include <limits>
#include <sstream>

namespace tsm {
namespace {

constexpr double coordinate_match = 1e-9;  // × model size (docs/format.md)

std::string point_text(const Eigen::Vector2d& p) {
  std::ostringstream os;
  os << "[" << p.x() << ", " << p.y() << "]";
  return os.str();
}

}  // namespace

int node_at(const Model& model, const Eigen::Vector2d& point, std::string& problem) {
  const double tolerance = coordinate_match * model.size;
  int found = -1, matches = 0, nearest = -1;
  double nearest_distance = std::numeric_limits<double>::infinity();
  for (int k = 0; k < model.node_count(); ++k) {
    const double distance = (model.nodes[k].position - point).norm();
    if (distance <= tolerance && matches++ == 0) found = k;
    if (distance < nearest_distance) nearest_distance = distance, nearest = k;
  }
  if (matches == 1) return found;
  std::ostringstream os;
  if (matches > 1) {
    os << matches << " nodes at " << point_text(point) << " (use a node id)";
  } else {
    os << "no node at " << point_text(point);
    if (nearest >= 0)
      os << " (the nearest, node " << model.nodes[nearest].id << ", is at " << point_text(model.nodes[nearest].position)
         << ", " << nearest_distance << " away)";
  }
  problem = os.str();
  return -1;
}

}  // namespace tsm
