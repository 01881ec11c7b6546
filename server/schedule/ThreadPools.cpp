#include "schedule/ThreadPools.hpp"

#include <algorithm>

namespace orthosim::server {

namespace {
std::size_t atLeastOne(int threads) { return static_cast<std::size_t>(std::max(1, threads)); }
}  // namespace

ThreadPools::ThreadPools(int previewThreads, BackgroundThreads background, int renderThreads)
    : preview_(previewThreads),
      render_(renderThreads),
      openings_(atLeastOne(background.openings)),
      faceFits_(atLeastOne(background.faceFits)),
      exports_(atLeastOne(background.exports)),
      requests_(atLeastOne(background.requests)) {}

ThreadPools::~ThreadPools() = default;

void ThreadPools::stopPreviewsAndFrames() {
  preview_.stop();
  render_.stop();
}

void ThreadPools::stopBackground() {
  for (boost::asio::thread_pool* pool : {&openings_, &faceFits_, &exports_, &requests_}) pool->stop();
  for (boost::asio::thread_pool* pool : {&openings_, &faceFits_, &exports_, &requests_}) pool->join();
}

}  // namespace orthosim::server
