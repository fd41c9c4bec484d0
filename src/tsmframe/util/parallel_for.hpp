#pragma once
// Loops shared out over OpenMP's threads only where a team would run them. GCC's libgomp makes
// a futex system call at the end of every parallel construct, even one whose `if` clause is
// false or whose team has a single thread: 1.3 µs on the project's VM (bench/README "Ninth
// session"), and a Newton iteration passed through about seven such constructs that ran
// serially. Here the choice is a C++ branch, so a serial loop is a plain loop. The loop body
// and its order per index are the same either way: results do not depend on the branch taken.

#include <omp.h>

namespace tsm::util {

/// Models smaller than this (elements, or node blocks of the tangent) run every loop on one
/// thread. A region's wake-up of the second thread costs ~1 µs on this VM while it still spins
/// and the first regions of a process up to a few ms (starting the thread), so below this the
/// second thread does not pay. Measured in one process (bench/README "Twelfth session", median of
/// 40 runs, three alternations): a 1,000-element chain 83–134 ns on two threads against 122 on
/// one (faster in 2 of 3), 1,500 elements 79 against 123 in all three, 500 elements 97–161
/// against 120, 250 elements 114–116 against 118–120. (The ninth session measured two threads
/// slower at 1,000; the factorisation's parallel top and the prefetching have changed that.)
constexpr int smallest_shared_model = 1000;

/// Whether a loop that `wants` threads gets a parallel region: only if more than one thread is
/// available (omp_get_max_threads reads a setting; no system call).
inline bool team_available(bool wants) { return wants && omp_get_max_threads() > 1; }

/// body(i) for i in [begin, end): schedule(static) on the team where `wants` and threads allow.
template <class Index, class Body>
void parallel_for_static(Index begin, Index end, bool wants, const Body& body) {
  if (!team_available(wants)) {
    for (Index i = begin; i < end; ++i) body(i);
    return;
  }
#pragma omp parallel for schedule(static)
  for (Index i = begin; i < end; ++i) body(i);
}

/// body(i) for i in [begin, end): schedule(dynamic, 1) on the team where `wants` and threads allow.
template <class Index, class Body>
void parallel_for_dynamic(Index begin, Index end, bool wants, const Body& body) {
  if (!team_available(wants)) {
    for (Index i = begin; i < end; ++i) body(i);
    return;
  }
#pragma omp parallel for schedule(dynamic, 1)
  for (Index i = begin; i < end; ++i) body(i);
}

/// Whether body(i) is true for every i in [begin, end), schedule(dynamic, 1) as above. Once a
/// body has failed, the bodies a thread has not yet started are skipped (none is left half done).
template <class Index, class Body>
bool parallel_all_dynamic(Index begin, Index end, bool wants, const Body& body) {
  bool ok = true;
  if (!team_available(wants)) {
    for (Index i = begin; i < end && ok; ++i) ok = body(i);
    return ok;
  }
#pragma omp parallel for schedule(dynamic, 1) reduction(&& : ok)
  for (Index i = begin; i < end; ++i) ok = ok && body(i);
  return ok;
}

}  // namespace tsm::util
