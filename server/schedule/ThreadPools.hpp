#pragma once
// The server's thread pools, shared by every session: sessions' coarse solves, the threads that
// draw the sessions' frames (a session's frames one at a time: its renderer is used by one thread
// at a time, which binds its context for each frame), and patient imports,
// one at a time, off the network threads. Below the previews, the background pools: each kind of
// slow work has its own, so that no kind queues behind another (a meshing behind a save, a save
// behind a face fit) and none holds a preview thread: case openings and rebuilds (meshing: tens of
// seconds), face fits (up to their time budget), exports, and the disk and Redis requests the
// network threads must not wait for (saved plans, listings, job submissions).
#include <boost/asio/thread_pool.hpp>
#include <cstddef>

#include "schedule/RoundRobinExecutor.hpp"

namespace orthosim::server {

// Threads of each background pool (at least one each).
struct BackgroundThreads {
  int openings = 1;
  int faceFits = 1;
  int exports = 1;
  int requests = 1;
};

class ThreadPools {
 public:
  explicit ThreadPools(int previewThreads, BackgroundThreads background = {}, int renderThreads = 1);
  ~ThreadPools();

  // Sessions take turns on both (schedule/RoundRobinExecutor).
  RoundRobinExecutor& preview() { return preview_; }
  RoundRobinExecutor& render() { return render_; }
  boost::asio::thread_pool& import() { return import_; }
  boost::asio::thread_pool& openings() { return openings_; }
  boost::asio::thread_pool& faceFits() { return faceFits_; }
  boost::asio::thread_pool& exports() { return exports_; }
  boost::asio::thread_pool& requests() { return requests_; }
  // Queued previews and frames never start; running ones see their session's cancel. Waits for them.
  void stopPreviewsAndFrames();
  // Queued background work never starts; waits for the running work (closed sessions cancel theirs).
  void stopBackground();

 private:
  RoundRobinExecutor preview_;
  RoundRobinExecutor render_;
  boost::asio::thread_pool import_{1};
  boost::asio::thread_pool openings_;
  boost::asio::thread_pool faceFits_;
  boost::asio::thread_pool exports_;
  boost::asio::thread_pool requests_;
};

}  // namespace orthosim::server
