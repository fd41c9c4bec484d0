#pragma once
// What a result says about its path besides its steps: the limit points, and notes on what a
// converged path should not hide (a jump across a snap-back or a snap-through, unstable
// equilibria, contacts that slid off a free end, strains past the small-strain law's reach,
// steps accepted on round-off because nothing was carried).

#include <string>
#include <vector>

#include "tsmframe/model/model.hpp"
#include "tsmframe/solver/step_record.hpp"

namespace tsm::solver {

/// Limit points: converged steps whose λ is a strict local extremum of the path, each with its
/// location where the stepping found it (`refined`, by step), and marked where a contact point
/// passed an element end between the steps around it.
std::vector<LimitPoint> limit_points(const std::vector<StepRecord>& steps, const std::vector<RefinedLimit>& refined = {});

/// The note for linearised buckling that resolved `found` of the `asked` modes, the next lost in
/// round-off (solver/buckling).
std::string unresolved_buckling_note(int asked, size_t found);

/// The note for linearised buckling asked at converged step `step` (0: the last) that the run
/// did not reach.
std::string unreached_buckling_note(int step);

/// Sets result.limit_points and result.notes from its steps (and its critical points).
void close_path(const Model& model, RunResult& result, ControlType control);

}  // namespace tsm::solver
