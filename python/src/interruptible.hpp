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
/// `poll` (if any) runs with the GIL held beside each check of the signals and once when the work
/// is done — where a progress callback reports what the work queued; what it raises stops the
/// work like Ctrl-C and is raised here.
void run_interruptible(const std::function<void(const solver::StopRequest*)>& work,
                       const std::function<void()>& poll = {});

}  // namespace tsm::python
