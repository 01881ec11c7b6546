#include "schedule/ThreadPools.hpp"

#include <algorithm>

namespace orthosim::server {

ThreadPools::ThreadPools(int previewThreads) : preview_(static_cast<std::size_t>(std::max(1, previewThreads))) {}

ThreadPools::~ThreadPools() = default;

void ThreadPools::stopPreviewsAndFrames() {
  preview_.stop();
  preview_.join();
  render_.stop();
  render_.join();
}

}  // namespace orthosim::server
