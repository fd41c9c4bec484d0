#include "tsmframe/io/section_table.hpp"

#include <nlohmann/json.hpp>

#include "tsmframe/io/json_input.hpp"

namespace tsm::io {

using nlohmann::json;

SectionTable::SectionTable(const json& doc) {
  if (!doc.contains("materials")) fail("materials", "missing (required)");
  expect_object(doc["materials"], "materials");
  for (const auto& item : doc["materials"].items()) {
    const std::string path = child("materials", item.key());
    const json& m = item.value();
    expect_object(m, path);
    check_keys(m, path, {"E", "G", "nu", "density"});
    Material material;
    material.E = positive(required_number(m, "E", path), child(path, "E"));
    if (m.contains("G") && m.contains("nu")) fail(path, "give G or nu, not both");
    if (auto G = optional_number(m, "G", path)) material.G = positive(*G, child(path, "G"));
    if (auto nu = optional_number(m, "nu", path)) {
      if (!(*nu > -1.0 && *nu < 0.5)) fail(child(path, "nu"), "Poisson's ratio must lie in (-1, 0.5)");
      material.G = material.E / (2.0 * (1.0 + *nu));
    }
    if (auto density = optional_number(m, "density", path)) material.density = positive(*density, child(path, "density"));
    materials_[item.key()] = material;
  }
  if (!doc.contains("sections")) fail("sections", "missing (required)");
  expect_object(doc["sections"], "sections");
  for (const auto& item : doc["sections"].items()) {
    const std::string path = child("sections", item.key());
    const json& s = item.value();
    expect_object(s, path);
    check_keys(s, path, {"A", "I", "shear_area"});
    Section section;
    section.A = positive(required_number(s, "A", path), child(path, "A"));
    section.I = positive(required_number(s, "I", path), child(path, "I"));
    if (auto shear = optional_number(s, "shear_area", path)) section.shear_area = positive(*shear, child(path, "shear_area"));
    sections_[item.key()] = section;
  }
}

element::SectionStiffness SectionTable::stiffness(const json& m, const std::string& path, BeamTheory theory) const {
  if (!m.contains("material")) fail(child(path, "material"), "missing (required)");
  if (!m.contains("section")) fail(child(path, "section"), "missing (required)");
  const std::string material_name = string(m["material"], child(path, "material"));
  const std::string section_name = string(m["section"], child(path, "section"));
  const auto material = materials_.find(material_name);
  if (material == materials_.end()) fail(child(path, "material"), "unknown material " + quote_text(material_name));
  const auto section = sections_.find(section_name);
  if (section == sections_.end()) fail(child(path, "section"), "unknown section " + quote_text(section_name));
  element::SectionStiffness s;
  s.EA = material->second.E * section->second.A;
  s.EI = material->second.E * section->second.I;
  if (theory == BeamTheory::timoshenko) {
    if (!material->second.G) fail(child(path, "material"), "material " + quote_text(material_name) + " has no G (or nu), which Timoshenko elements need");
    if (!section->second.shear_area) fail(child(path, "section"), "section " + quote_text(section_name) + " has no shear_area, which Timoshenko elements need");
    s.shear_flexibility = s.EI / (*material->second.G * *section->second.shear_area);  // Ψ = EI/(G A_s), Eq. 8
  }
  return s;
}

std::optional<double> SectionTable::mass_per_length(const json& m) const {
  const Material& material = materials_.at(m["material"].get<std::string>());
  if (!material.density) return std::nullopt;
  return *material.density * sections_.at(m["section"].get<std::string>()).A;
}

bool SectionTable::any_density() const {
  for (const auto& [name, material] : materials_)
    if (material.density) return true;
  return false;
}

}  // namespace tsm::io
