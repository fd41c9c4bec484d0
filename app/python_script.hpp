#pragma once
// The scripts the command runs in Python (scripts/: plots, reports, a study on a Dask cluster).

#include <string>
#include <vector>

namespace tsm::app {

/// Runs one of scripts/ with Debian's python3 (no shell: paths pass as they are); its exit
/// status (−1 where it could not be started or did not exit). `quiet`: its standard output goes
/// to /dev/null.
int run_script(const char* script, const std::vector<std::string>& arguments, bool quiet = false);

/// Where the tsmframe Python package of this build is (for the scripts' sys.path).
const char* python_package_directory();

}  // namespace tsm::app
