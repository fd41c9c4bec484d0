#pragma once
// ParaView output: one .vtu (VTK XML unstructured grid, ASCII) per converged step and a .pvd
// series that lists them with the load factor as time.
//
// Each element is drawn as its deflected curve in curve_segments segments (io/element_curves: the
// element's own shape under its end rotations relative to the current chord, hinges and end
// springs condensed — Hermite cubic for Euler–Bernoulli, with the shear term for Timoshenko).
// Point data: "displacement" (of the material point: current − drawn position, z = 0) and
// "rotation" (Θ interpolated along the element; exact at the nodes). Cell data per element:
// "N", "M_i", "M_j", "Y" (0 without contact), "element_id". Contact points are extra vertex
// cells carrying the point vector "contact_force" (the force the contact node exerts on the beam).

#include <string>
#include <vector>

#include "tsmframe/model/model.hpp"
#include "tsmframe/solver/step_record.hpp"

namespace tsm::io {

/// Writes the .vtu of one converged step that carries state. Throws SystemError where the
/// system fails (output_file.hpp).
void write_vtu(const std::string& path, const Model& model, const solver::StepRecord& step);

/// Writes the .pvd series: (load factor, .vtu file name relative to the .pvd) per step.
void write_pvd(const std::string& path, const std::vector<std::pair<double, std::string>>& steps);

/// The linearised buckling modes (analysis.buckling) in `directory`: buckling-mode-K.vtu each —
/// the frame as drawn moved by the mode, scaled so that its largest translation is a tenth of the
/// model's size, in the step files' form ("displacement" the scaled mode, forces zero) — and
/// buckling.pvd listing them with their critical load factors. Nothing where there are none.
void write_buckling_vtu(const std::string& directory, const Model& model, const solver::Buckling& buckling);

}  // namespace tsm::io
