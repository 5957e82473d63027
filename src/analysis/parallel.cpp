#include "analysis/parallel.hpp"

#include <algorithm>
#include <atomic>
#include <thread>
#include <vector>

namespace mechkin {

int ThreadCount(int threads) {
  if (threads > 0) return threads;
  return std::max(1u, std::thread::hardware_concurrency());
}

void ParallelFor(int count, int threads, const std::function<void(int, int)>& job,
                 const std::function<bool()>& stop) {
  const int n = std::min(ThreadCount(threads), std::max(count, 1));
  std::atomic<int> next{0};
  auto work = [&](int thread) {
    for (int i = next++; i < count && !(stop && stop()); i = next++) job(i, thread);
  };
  std::vector<std::thread> pool;
  for (int k = 1; k < n; ++k) pool.emplace_back(work, k);
  work(0);
  for (auto& th : pool) th.join();
}

}  // namespace mechkin
