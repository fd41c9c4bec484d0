#pragma once
// A model file's "materials" and "sections" (docs/format.md), read strictly, and a member's section
// stiffness from the material and section it names: EA, EI and, for Timoshenko elements,
// Ψ = EI/(G A_s) (Eq. 8); and its mass per length, where its material has a density.

#include <map>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>

#include "tsmframe/element/force_law.hpp"
#include "tsmframe/model/model.hpp"

namespace tsm::io {

class SectionTable {
 public:
  /// Reads the document's "materials" and "sections" (both required). Throws InputError.
  explicit SectionTable(const nlohmann::json& document);

  /// The stiffness of the member at `path` (the object `member`, naming its "material" and
  /// "section") as elements of `theory`. Throws InputError (an unknown name, no G or shear area
  /// where Timoshenko needs them).
  element::SectionStiffness stiffness(const nlohmann::json& member, const std::string& path, BeamTheory theory) const;
  /// The mass per unit length, density × A, of the member at `path` (its material and section
  /// already found by stiffness()); none where its material has no density.
  std::optional<double> mass_per_length(const nlohmann::json& member) const;
  /// Whether any material has a density.
  bool any_density() const;

 private:
  struct Material {
    double E = 0.0;
    std::optional<double> G;
    std::optional<double> density;  ///< mass per unit volume (self-weight under "gravity")
  };
  struct Section {
    double A = 0.0, I = 0.0;
    std::optional<double> shear_area;
  };
  std::map<std::string, Material> materials_;
  std::map<std::string, Section> sections_;
};

}  // namespace tsm::io
