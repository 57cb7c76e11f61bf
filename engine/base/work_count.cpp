#include "engine/base/work_count.hpp"

#include <atomic>

namespace kinema {
namespace {

std::atomic<std::uint64_t> counts[static_cast<int>(Work::count_)];

}  // namespace

void count_work(Work work) { counts[static_cast<int>(work)].fetch_add(1, std::memory_order_relaxed); }

std::uint64_t work_done_in_process(Work work) {
  return counts[static_cast<int>(work)].load(std::memory_order_relaxed);
}

}  // namespace kinema
