// Runs fn(i) for i in [0, count) on up to `threads` threads. Results must be written by index
// so that the outcome does not depend on scheduling (determinism under a seed).
#pragma once

#include <algorithm>
#include <atomic>
#include <thread>
#include <vector>

namespace sps {

template <typename Fn>
void parallel_for(int count, int threads, Fn&& fn) {
  threads = std::max(1, std::min(threads, count));
  if (threads == 1) {
    for (int i = 0; i < count; ++i) fn(i);
    return;
  }
  std::atomic<int> next{0};
  auto worker = [&] {
    for (int i = next++; i < count; i = next++) fn(i);
  };
  std::vector<std::thread> pool;
  pool.reserve(static_cast<std::size_t>(threads - 1));
  for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (auto& th : pool) th.join();
}

}  // namespace sps
