#pragma once
// A std::chrono clock that reads the calling thread's CPU time (POSIX CLOCK_THREAD_CPUTIME_ID), for
// the simulator's phase timings: on a shared machine wall time also counts the waits for a core.
#include <chrono>
#include <ctime>

namespace dresskit::cloth {

struct ThreadCpuClock {
  using duration = std::chrono::nanoseconds;
  using rep = duration::rep;
  using period = duration::period;
  using time_point = std::chrono::time_point<ThreadCpuClock>;
  static constexpr bool is_steady = true;
  static time_point now() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return time_point(duration(static_cast<rep>(t.tv_sec) * 1000000000 + t.tv_nsec));
  }
};

}  // namespace dresskit::cloth
