#pragma once
// Bounds on what one client may send or hold, so that no request can exhaust the server.
#include <chrono>
#include <cstddef>

namespace orthosim::net {

struct HttpLimits {
  std::size_t headerBytes = 16 * 1024;   // request line and headers; browsers send about 1-2 KiB
  std::size_t bodyBytes = 64 * 1024;     // request body; the HTTP API takes none yet
  std::chrono::seconds idleTimeout{30};  // a connection silent this long is closed
};

}  // namespace orthosim::net
