#pragma once
// The server's thread pools, shared by every session: sessions' coarse solves and case openings,
// the one thread that draws every session's frames (a session's renderer is used by one thread),
// and patient imports, one at a time, off the network threads.
#include <boost/asio/thread_pool.hpp>
#include <cstddef>

namespace orthosim::server {

class ThreadPools {
 public:
  explicit ThreadPools(int previewThreads);
  ~ThreadPools();

  boost::asio::thread_pool& preview() { return preview_; }
  boost::asio::thread_pool& render() { return render_; }
  boost::asio::thread_pool& import() { return import_; }
  // Queued previews and frames never start; running ones see their session's cancel. Waits for them.
  void stopPreviewsAndFrames();

 private:
  boost::asio::thread_pool preview_;
  boost::asio::thread_pool render_{1};
  boost::asio::thread_pool import_{1};
};

}  // namespace orthosim::server
