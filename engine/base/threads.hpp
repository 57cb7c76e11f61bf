// Work shared out among threads: each runs the same `work`, which takes its share itself
// (e.g. from an atomic counter); this thread is one of them. The first exception any
// throws is thrown here, once all have ended; `on_failure` runs in the failing thread
// (to tell the others to stop taking work).
#pragma once

#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace kinema {

template <class Work, class OnFailure>
void run_on_threads(unsigned threads, const Work& work, const OnFailure& on_failure) {
  std::exception_ptr failure;
  std::mutex failure_lock;
  const auto guarded = [&]() {
    try {
      work();
    } catch (...) {
      {
        const std::lock_guard<std::mutex> lock(failure_lock);
        if (!failure) failure = std::current_exception();
      }
      on_failure();
    }
  };
  std::vector<std::thread> workers;
  for (unsigned t = 1; t < threads; ++t) workers.emplace_back(guarded);
  guarded();
  for (std::thread& worker : workers) worker.join();
  if (failure) std::rethrow_exception(failure);
}

template <class Work>
void run_on_threads(unsigned threads, const Work& work) {
  run_on_threads(threads, work, [] {});
}

}  // namespace kinema
