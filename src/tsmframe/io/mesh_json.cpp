#include "tsmframe/io/mesh_json.hpp"

namespace tsm::io {

void write_mesh(JsonWriter& w, const Model& model) {
  w.newline().key("nodes").begin_array();
  for (const Node& n : model.nodes) {
    w.newline().begin_object();
    w.key("id").value(n.id).key("x").value(n.position.x()).key("y").value(n.position.y());
    w.end_object();
  }
  w.end_array();
  w.newline().key("elements").begin_array();
  for (const Element& e : model.elements) {
    w.newline().begin_object();
    w.key("id").value(e.id);
    w.key("nodes").begin_array().value(model.nodes[e.start].id).value(model.nodes[e.end].id).end_array();
    w.key("element").value(theory_name(e.theory));
    w.key("member").value(e.member);
    if (e.release_start || e.release_end)  // a hinge at that end: no moment there
      w.key("release").value(e.release_start && e.release_end ? "both" : e.release_start ? "start" : "end");
    if (const double fi = model.flexibility_start(e), fj = model.flexibility_end(e); fi > 0.0 || fj > 0.0) {
      w.key("end_springs").begin_object();  // semi-rigid: the springs' stiffness
      if (fi > 0.0) w.key("start").value(1.0 / fi);
      if (fj > 0.0) w.key("end").value(1.0 / fj);
      w.end_object();
    }
    w.end_object();
  }
  w.end_array();
}

}  // namespace tsm::io
