#pragma once
// A small blocking HTTP client over a real socket to 127.0.0.1, for the server tests.
#include <boost/beast/http.hpp>
#include <chrono>
#include <string>
#include <vector>

namespace orthosim::test {

using HttpReply = boost::beast::http::response<boost::beast::http::string_body>;

// Sends `method target` (the target verbatim, not normalised) on a fresh connection and reads
// the reply. Throws boost::system::system_error on a network failure.
HttpReply httpRequest(unsigned short port, boost::beast::http::verb method, const std::string& target);
inline HttpReply httpGet(unsigned short port, const std::string& target) {
  return httpRequest(port, boost::beast::http::verb::get, target);
}

// Writes `bytes` as they are (any requests, well-formed or not), then reads replies until the
// server closes the connection (at most `silence` without a byte: a scan's import takes longer
// than the usual 10 s). Throws when no reply arrives.
std::vector<HttpReply> httpRaw(unsigned short port, const std::string& bytes,
                               std::chrono::seconds silence = std::chrono::seconds(10));

}  // namespace orthosim::test
