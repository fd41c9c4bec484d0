#pragma once
// Ctrl-C (SIGINT) and a termination request (SIGTERM: a batch system's time limit) end a run at
// its next step boundary: the handler only sets the stop request the step loops poll. A second
// signal more than a second after the first ends the program at once, as by default (the outputs
// then stay the previous ones: io/output_directory.hpp); one sooner is the same request again
// (timeout(1) signals the program, then its process group). SIGXFSZ is ignored: a file beyond
// the size limit (ulimit -f) is then a write that fails with "File too large", exit 3.

#include "tsmframe/solver/stop_request.hpp"

namespace tsm::app {

/// Installs the handlers; returns the stop request they set.
const solver::StopRequest& install_stop_signals();
/// The signal that set the stop request ("SIGINT", "SIGTERM"); null while none came.
const char* stop_signal_name();

}  // namespace tsm::app
