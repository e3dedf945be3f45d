#pragma once
// The engine's OpenMP settings, in one place (internal to src/dem).
#include <cstdint>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace gjkdem::dem::detail {

// Below these sizes a loop runs on one thread: waking the team costs more
// than the loop (measured: a tiny scene ran 150x slower when another process
// used the cores and the team spin-waited).
// Loops doing little per body (kicks, force resets, box checks: about 10 ns)
// wait for more bodies than the drift (rotations: about 80 ns per body).
inline constexpr std::int64_t kMinParallelBodies = 4096;
inline constexpr std::int64_t kMinParallelRotations = 512;
inline constexpr std::int64_t kMinParallelContacts = 64;

/// Threads for a step: `requested`, or all cores for 0.
inline int thread_count(int requested) {
#ifdef _OPENMP
  return requested > 0 ? requested : omp_get_max_threads();
#else
  (void)requested;
  return 1;
#endif
}

inline int thread_id() {
#ifdef _OPENMP
  return omp_get_thread_num();
#else
  return 0;
#endif
}

}  // namespace gjkdem::dem::detail
