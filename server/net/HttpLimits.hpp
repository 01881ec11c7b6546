#pragma once
// Bounds on what one client may send or hold, so that no request can exhaust the server.
#include <chrono>
#include <cstddef>

namespace orthosim::net {

struct HttpLimits {
  std::size_t headerBytes = 16 * 1024;  // request line and headers; browsers send about 1-2 KiB
  std::size_t bodyBytes = 64 * 1024;    // request body of every route but the upload
  // A patient's upload (POST /api/patients): skin, bones and texture as exported, uncompressed.
  std::size_t uploadBytes = 256 * 1024 * 1024;
  // Uploads received or imported at once (net/UploadSlots); each is streamed to a file, so what
  // one takes in memory is Beast's buffers and the import's.
  int maxUploads = 4;
  std::chrono::seconds uploadTimeout{300};  // to send the upload over a slow link
  std::chrono::seconds idleTimeout{30};     // a connection silent this long is closed
};

}  // namespace orthosim::net
