#pragma once
// Loops shared out over OpenMP's threads only where a team would run them. GCC's libgomp makes
// a futex system call at the end of every parallel construct, even one whose `if` clause is
// false or whose team has a single thread, and a Newton iteration passes through several such
// constructs that run serially. Here the choice is a C++ branch, so a serial loop is a plain
// loop. The loop body and its order per index are the same either way: results do not depend on
// the branch taken.

#include <omp.h>

namespace tsm::util {

/// Models smaller than this (elements, or node blocks of the tangent) run every loop on one
/// thread: waking the second thread for each region, and starting it in a process's first
/// regions, costs more than it saves below this size (bench/README.md, the two-thread crossover).
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
