#pragma once
// Which criterion ended a converged Newton step (convergence.hpp decides it).

namespace tsm::solver {

enum class Criterion {
  none,             ///< not converged
  force,            ///< the relative residual within the tolerance
  round_off,        ///< the corrections, or the residual, at rounding level
  nothing_carried,  ///< round-off where the structure carries next to nothing (its residual is noise)
};

/// The spelling in results ("force", "round-off"; "" for none).
inline const char* criterion_name(Criterion criterion) {
  switch (criterion) {
    case Criterion::none: return "";
    case Criterion::force: return "force";
    case Criterion::round_off:
    case Criterion::nothing_carried: return "round-off";
  }
  return "";
}

}  // namespace tsm::solver
