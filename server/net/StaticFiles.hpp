#pragma once
// GET/HEAD of a file under the web folder, streamed from disk with its Content-Type.
#include <string_view>

#include "net/HttpMessages.hpp"
#include "net/WebRoot.hpp"

namespace orthosim::net {

// 200 with the file; 404 (JSON error) when the web root has no such file; 400 when the path
// tries to leave the folder. decodedPath: see WebRoot::find.
Response serveStaticFile(const WebRoot& web, std::string_view decodedPath, const ReplyTo& to);

}  // namespace orthosim::net
