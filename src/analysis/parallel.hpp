// Independent runs on all cores (tolerance Monte-Carlo, sweeps): plain threads
// pulling indices from one counter, each with its own scratch (thread index).
#pragma once

#include <functional>

namespace mechkin {

/// Runs job(i, thread) for i = 0..count−1 on `threads` threads (0: all cores). When
/// `stop` is set and returns true, no further index is started (the running ones finish).
void ParallelFor(int count, int threads, const std::function<void(int index, int thread)>& job,
                 const std::function<bool()>& stop = {});
/// The number of threads ParallelFor uses for `threads`.
int ThreadCount(int threads);

}  // namespace mechkin
