#pragma once
// The HTTP message types the server reads and writes, and how a reply mirrors its request.
#include <boost/beast/http.hpp>
#include <variant>

namespace orthosim::net {

namespace http = boost::beast::http;

using Request = http::request<http::string_body>;
using StringResponse = http::response<http::string_body>;
using FileResponse = http::response<http::file_body>;
// A handler answers with text (JSON, errors) or streams a file straight from disk.
using Response = std::variant<StringResponse, FileResponse>;

// What a response copies from its request: HTTP version, keep-alive, and whether the body is
// omitted (HEAD).
struct ReplyTo {
  unsigned version = 11;
  bool keepAlive = false;
  bool headOnly = false;
};

inline ReplyTo replyTo(const Request& request) {
  return {request.version(), request.keep_alive(), request.method() == http::verb::head};
}

}  // namespace orthosim::net
