#include "tsmframe/solver/status.hpp"

namespace tsm::solver {

const char* status_name(Status status) {
  switch (status) {
    case Status::converged: return "converged";
    case Status::diverged: return "diverged";
    case Status::max_iterations: return "max-iterations";
    case Status::singular: return "singular";
    case Status::cutback_limit: return "cutback-limit";
    case Status::contact_chatter: return "contact-chatter";
    case Status::step_limit: return "step-limit";
    case Status::interrupted: return "interrupted";
  }
  return "unknown";
}

}  // namespace tsm::solver
