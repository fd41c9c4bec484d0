#include "tsmframe/io/vtk_writer.hpp"

#include <algorithm>
#include <cmath>

#include "tsmframe/io/element_curves.hpp"
#include "tsmframe/io/json_writer.hpp"
#include "tsmframe/io/output_file.hpp"
#include "tsmframe/io/section_diagrams.hpp"

namespace tsm::io {
namespace {

struct Curve {
  std::vector<Eigen::Vector2d> points;        ///< current positions along the element
  std::vector<Eigen::Vector2d> displacement;  ///< current − drawn position of those material points
  std::vector<double> rotation;
  std::vector<element::SectionStation> sections;  ///< N, V, M there (io/section_diagrams)
};

Curve drawn_curve(const Model& model, size_t element, const solver::StepRecord& step,
                  const std::vector<element::SectionStation>& stations) {
  const Element& e = model.elements[element];
  const Eigen::VectorXd& D = step.displacements;
  Curve c;
  c.points.resize(curve_segments + 1);
  element_curve(model, e, D, step.element_forces.segment<3>(3 * element), c.points);
  const Eigen::Vector2d Xi = model.nodes[e.start].position, Xj = model.nodes[e.end].position;
  const double rotation_i = D[dofs_per_node * e.start + rz], rotation_j = D[dofs_per_node * e.end + rz];
  for (int k = 0; k <= curve_segments; ++k) {
    const double s = static_cast<double>(k) / curve_segments;
    c.displacement.push_back(c.points[k] - (Xi + s * (Xj - Xi)));
    c.rotation.push_back((1.0 - s) * rotation_i + s * rotation_j);
    c.sections.push_back(element::section_at(stations, s * stations.back().x));
  }
  return c;
}

}  // namespace

void write_vtu(const std::string& path, const Model& model, const solver::StepRecord& step) {
  const Eigen::VectorXd& D = step.displacements;
  std::vector<Curve> curves;
  curves.reserve(model.elements.size());
  const std::vector<std::vector<element::SectionStation>> diagrams = section_diagrams(model, step);
  for (size_t e = 0; e < model.elements.size(); ++e) curves.push_back(drawn_curve(model, e, step, diagrams[e]));
  struct ContactPoint {
    int node;
    Eigen::Vector2d position, force;
    double Y;
    Eigen::Vector2d friction = Eigen::Vector2d::Zero();  ///< the friction force along the touched element's chord
    int friction_status = 0;                             ///< 1 stick, 2 slip, 0 neither
  };
  const bool frictional = std::any_of(model.contacts.begin(), model.contacts.end(), [](const ContactSpec& c) { return c.friction > 0.0; });
  std::vector<ContactPoint> contacts;
  std::vector<double> element_Y(model.elements.size(), 0.0);
  for (size_t k = 0; k < step.contacts.size(); ++k) {
    const solver::ContactPoint& c = step.contacts[k];
    if (c.element < 0) continue;
    element_Y[c.element] = c.Y;
    if (c.partner >= 0) element_Y[c.partner] = c.partner_Y;  // a vertex: both elements push
    const int node = model.contacts[k].node;
    contacts.push_back({node, model.nodes[node].position + D.segment<2>(dofs_per_node * node), c.push, c.Y});
    if (c.friction == contact::FrictionStatus::stick || c.friction == contact::FrictionStatus::slip) {
      const Element& e = model.elements[c.element];
      const Eigen::Vector2d chord = (model.nodes[e.end].position + D.segment<2>(dofs_per_node * e.end)) -
                                    (model.nodes[e.start].position + D.segment<2>(dofs_per_node * e.start));
      contacts.back().friction = c.tangential * chord.normalized();
      contacts.back().friction_status = c.friction == contact::FrictionStatus::stick ? 1 : 2;
    }
  }
  const size_t per = curve_segments + 1, n_points = curves.size() * per + contacts.size();
  const size_t n_cells = curves.size() + contacts.size();
  write_output_file(path, [&](std::ostream& out) {
    auto num = [](double x) { return format_number(std::isfinite(x) ? x : 0.0); };
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\">\n"
        << "<UnstructuredGrid>\n<Piece NumberOfPoints=\"" << n_points << "\" NumberOfCells=\"" << n_cells << "\">\n";
    out << "<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
    for (const Curve& c : curves)
      for (const Eigen::Vector2d& p : c.points) out << num(p.x()) << ' ' << num(p.y()) << " 0\n";
    for (const ContactPoint& c : contacts) out << num(c.position.x()) << ' ' << num(c.position.y()) << " 0\n";
    out << "</DataArray>\n</Points>\n<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
    for (size_t k = 0; k < curves.size(); ++k) {
      for (size_t p = 0; p < per; ++p) out << k * per + p << (p + 1 < per ? ' ' : '\n');
    }
    for (size_t k = 0; k < contacts.size(); ++k) out << curves.size() * per + k << '\n';
    out << "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
    for (size_t k = 0; k < curves.size(); ++k) out << (k + 1) * per << '\n';
    for (size_t k = 0; k < contacts.size(); ++k) out << curves.size() * per + k + 1 << '\n';
    out << "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
    for (size_t k = 0; k < curves.size(); ++k) out << "4\n";  // VTK_POLY_LINE
    for (size_t k = 0; k < contacts.size(); ++k) out << "1\n";  // VTK_VERTEX
    out << "</DataArray>\n</Cells>\n<PointData Vectors=\"displacement\">\n";
    out << "<DataArray type=\"Float64\" Name=\"displacement\" NumberOfComponents=\"3\" format=\"ascii\">\n";
    for (const Curve& c : curves)
      for (const Eigen::Vector2d& u : c.displacement) out << num(u.x()) << ' ' << num(u.y()) << " 0\n";
    for (const ContactPoint& c : contacts)
      out << num(D[dofs_per_node * c.node]) << ' ' << num(D[dofs_per_node * c.node + 1]) << " 0\n";
    out << "</DataArray>\n<DataArray type=\"Float64\" Name=\"rotation\" format=\"ascii\">\n";
    for (const Curve& c : curves)
      for (double r : c.rotation) out << num(r) << '\n';
    for (size_t k = 0; k < contacts.size(); ++k) out << "0\n";
    out << "</DataArray>\n<DataArray type=\"Float64\" Name=\"contact_force\" NumberOfComponents=\"3\" format=\"ascii\">\n";
    for (size_t k = 0; k < curves.size() * per; ++k) out << "0 0 0\n";
    for (const ContactPoint& c : contacts) out << num(c.force.x()) << ' ' << num(c.force.y()) << " 0\n";
    if (frictional) {  // only where friction is: a frictionless model's files stay as they were
      out << "</DataArray>\n<DataArray type=\"Float64\" Name=\"friction_force\" NumberOfComponents=\"3\" format=\"ascii\">\n";
      for (size_t k = 0; k < curves.size() * per; ++k) out << "0 0 0\n";
      for (const ContactPoint& c : contacts) out << num(c.friction.x()) << ' ' << num(c.friction.y()) << " 0\n";
      out << "</DataArray>\n<DataArray type=\"Int32\" Name=\"friction_status\" format=\"ascii\">\n";
      for (size_t k = 0; k < curves.size() * per; ++k) out << "0\n";
      for (const ContactPoint& c : contacts) out << c.friction_status << '\n';
    }
    // The N, V, M diagrams along each element's curve (a contact point's jump between two points).
    for (const auto& [name, value] : {std::pair{"section_N", &element::SectionStation::N},
                                      std::pair{"section_V", &element::SectionStation::V},
                                      std::pair{"section_M", &element::SectionStation::M}}) {
      out << "</DataArray>\n<DataArray type=\"Float64\" Name=\"" << name << "\" format=\"ascii\">\n";
      for (const Curve& c : curves)
        for (const element::SectionStation& s : c.sections) out << num(s.*value) << '\n';
      for (size_t k = 0; k < contacts.size(); ++k) out << "0\n";
    }
    out << "</DataArray>\n</PointData>\n<CellData>\n";
    const char* names[] = {"N", "M_i", "M_j"};
    for (int f = 0; f < 3; ++f) {
      out << "<DataArray type=\"Float64\" Name=\"" << names[f] << "\" format=\"ascii\">\n";
      for (size_t k = 0; k < curves.size(); ++k) out << num(step.element_forces[3 * k + f]) << '\n';
      for (size_t k = 0; k < contacts.size(); ++k) out << "0\n";
      out << "</DataArray>\n";
    }
    out << "<DataArray type=\"Float64\" Name=\"Y\" format=\"ascii\">\n";
    for (size_t k = 0; k < curves.size(); ++k) out << num(element_Y[k]) << '\n';
    for (const ContactPoint& c : contacts) out << num(c.Y) << '\n';
    out << "</DataArray>\n<DataArray type=\"Int32\" Name=\"element_id\" format=\"ascii\">\n";
    for (const Element& e : model.elements) out << e.id << '\n';
    for (size_t k = 0; k < contacts.size(); ++k) out << "0\n";
    out << "</DataArray>\n</CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
  });
}

void write_pvd(const std::string& path, const std::vector<std::pair<double, std::string>>& steps) {
  write_output_file(path, [&](std::ostream& out) {
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"1.0\" byte_order=\"LittleEndian\">\n<Collection>\n";
    // ParaView needs increasing times: the step number, with the load factor in the name.
    for (size_t k = 0; k < steps.size(); ++k)
      out << "<DataSet timestep=\"" << k + 1 << "\" part=\"0\" file=\"" << steps[k].second << "\" name=\"load factor "
          << format_number(steps[k].first) << "\"/>\n";
    out << "</Collection>\n</VTKFile>\n";
  });
}

void write_buckling_vtu(const std::string& directory, const Model& model, const solver::Buckling& buckling) {
  if (buckling.modes.empty()) return;
  std::vector<std::pair<double, std::string>> files;
  for (size_t k = 0; k < buckling.modes.size(); ++k) {
    solver::StepRecord drawn;  // the mode in a step's form: moved by it, no forces
    drawn.step = static_cast<int>(k) + 1;
    drawn.load_factor = buckling.modes[k].load_factor;
    drawn.converged = drawn.has_state = true;
    drawn.displacements = 0.1 * model.size * buckling.modes[k].shape;  // its largest translation is 1
    drawn.element_forces = Eigen::VectorXd::Zero(3 * static_cast<Eigen::Index>(model.elements.size()));
    const std::string name = "buckling-mode-" + std::to_string(k + 1) + ".vtu";
    write_vtu(directory + "/" + name, model, drawn);
    files.emplace_back(drawn.load_factor, name);
  }
  write_pvd(directory + "/buckling.pvd", files);
}

}  // namespace tsm::io
