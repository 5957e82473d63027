// Independent runs on all cores (tolerance Monte-Carlo, sweeps): plain threads
// pulling indices from one counter, each with its own scratch (thread index).
#pragma once

#include <functional>

namespace mechkin {

/// Runs job(i, thread) for i = 0..count−1 on `threads` threads (0: all cores).
void ParallelFor(int count, int threads, const std::function<void(int index, int thread)>& job);
/// The number of threads ParallelFor uses for `threads`.
int ThreadCount(int threads);

}  // namespace mechkin
