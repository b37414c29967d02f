#include "lib/util/parallel_for.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace lutex {

int ResolveNumThreads(int requested) {
  if (requested > 0) return requested;
  const unsigned hardware = std::thread::hardware_concurrency();
  return hardware == 0 ? 1 : static_cast<int>(hardware);
}

void ParallelFor(std::size_t num_items, int num_threads, const std::function<void(std::size_t)>& body) {
  ParallelForOnWorkers(num_items, num_threads, [&](std::size_t item, int) { body(item); });
}

void ParallelForOnWorkers(std::size_t num_items, int num_threads,
                          const std::function<void(std::size_t item, int worker)>& body) {
  if (num_items == 0) return;
  const std::size_t workers =
      std::min<std::size_t>(static_cast<std::size_t>(ResolveNumThreads(num_threads)), num_items);
  if (workers == 1) {
    for (std::size_t i = 0; i < num_items; ++i) body(i, 0);
    return;
  }
  std::atomic<std::size_t> next{0};
  std::atomic<bool> failed{false};
  std::exception_ptr first_error;
  std::mutex error_mutex;
  auto worker = [&](int index) {
    while (!failed.load()) {
      const std::size_t i = next.fetch_add(1);
      if (i >= num_items) return;
      try {
        body(i, index);
      } catch (...) {
        std::lock_guard<std::mutex> lock(error_mutex);
        if (!first_error) first_error = std::current_exception();
        failed = true;
      }
    }
  };
  std::vector<std::thread> threads;
  threads.reserve(workers - 1);
  for (std::size_t t = 1; t < workers; ++t) threads.emplace_back(worker, static_cast<int>(t));
  worker(0);
  for (auto& thread : threads) thread.join();
  if (first_error) std::rethrow_exception(first_error);
}

}  // namespace lutex
