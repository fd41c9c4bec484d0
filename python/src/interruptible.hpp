#pragma once
// Ctrl-C in Python during a run or a study: the work runs on a thread of its own, the GIL
// released, while the calling thread lets Python handle its signals every 50 ms. A
// KeyboardInterrupt (or whatever a Python signal handler raises) requests the solver's stop: the
// work ends at its next step and the exception is raised here, in the caller.

#include <functional>

#include "src/bindings.hpp"
#include "tsmframe/solver/stop_request.hpp"

namespace tsm::python {

/// Runs `work` with the stop request it is to poll, as above; what `work` throws is rethrown.
void run_interruptible(const std::function<void(const solver::StopRequest*)>& work);

}  // namespace tsm::python
