// The threads of a step's parallel regions (parallel_for.hpp, the island solve), in place of
// `#pragma omp parallel`. libgomp starts and ends each region with barriers that wake their
// waiters by a futex system call even when every waiter spins; where a system call costs about a
// microsecond (a virtual machine), a region of two threads with nothing in it costs about 3 us,
// ten times a handoff between two cores. Here the caller bumps a generation word that the workers
// spin on and waits for a count of finished workers: one handoff each way, and a system call
// only to wake a worker that went to sleep (it spins for kSpinTime first, as libgomp's do).
//
// Each calling thread has its own team (a World stepped from several threads, one team each),
// started on its first region and grown to the largest region it has run; the workers end with
// their caller thread. The caller is thread 0 of its region. A region started inside a region
// runs as a team of one on the calling thread, as OpenMP's nested regions do by default.
#pragma once

#include <type_traits>
#include <utility>

namespace ragdoll_sim {

// {this thread's number, its region's size}; {0, 1} outside a region.
std::pair<int, int> teamSlot();

namespace thread_team_detail {
using Call = void (*)(void* body, int thread);
void run(int threads, Call call, void* body);
}  // namespace thread_team_detail

// body(t) on threads t = 0 .. threads - 1 (the caller is 0); returns when every thread is done.
// A nested or oversized region runs body(0) alone, so a body takes its team's size from teamSlot()
// or its work from a shared queue. body must not throw.
template <class Body>
void teamRun(int threads, Body&& body) {
  using B = std::remove_reference_t<Body>;
  thread_team_detail::run(
      threads, [](void* b, int t) { (*static_cast<B*>(b))(t); },
      const_cast<void*>(static_cast<const void*>(&body)));
}

}  // namespace ragdoll_sim
