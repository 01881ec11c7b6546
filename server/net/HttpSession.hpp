#pragma once
// One HTTP connection: reads a request, answers it through the Router, repeats while the client
// keeps the connection alive. An upload's body is streamed to a file, at most HttpLimits::maxUploads
// at once. Requests over the size limits get 413 / 431 and the connection is
// closed. A WebSocket upgrade to /ws hands the connection to a WebSocketSession. (Modelled on
// Beast's advanced_server.)
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <memory>
#include <optional>

#include "net/ConnectionContext.hpp"
#include "net/HttpMessages.hpp"
#include "net/UploadBody.hpp"

namespace orthosim::net {

class HttpSession : public std::enable_shared_from_this<HttpSession> {
 public:
  HttpSession(boost::asio::ip::tcp::socket&& socket, std::shared_ptr<const ConnectionContext> context);

  void start();

 private:
  void readRequest();
  // The headers first: an upload is checked and given its larger body limit before its body.
  void onHeader(boost::beast::error_code ec, std::size_t bytes);
  void onRead(boost::beast::error_code ec, std::size_t bytes);
  // An upload's body goes to a file (net/UploadBody), not into memory, once it has a slot.
  void readUpload();
  void onUploadRead(boost::beast::error_code ec, std::size_t bytes);
  void scanRequest();  // /api/scans/<token>/...: answered on the import pool
  void upgrade();
  void send(Response&& response, bool closeAfter);
  void onWrite(bool closeAfter, boost::beast::error_code ec, std::size_t bytes);
  // Half-closes, then reads and discards what the client still sends before closing: closing with
  // unread input would reset the connection and could destroy the error reply in flight.
  void drainThenClose();
  void onDrain(boost::beast::error_code ec, std::size_t bytes);

  boost::beast::tcp_stream stream_;
  boost::beast::flat_buffer buffer_;
  std::shared_ptr<const ConnectionContext> context_;
  const HttpLimits& limits_;
  std::optional<http::request_parser<http::string_body>> parser_;      // a fresh one per request
  std::optional<http::request_parser<http::file_body>> uploadParser_;  // an upload's, from parser_
  std::shared_ptr<UploadBody> upload_;                                 // its file and slot
  Response response_;                                                  // kept alive until its write completes
  std::size_t drained_ = 0;
};

}  // namespace orthosim::net
