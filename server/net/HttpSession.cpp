#include "net/HttpSession.hpp"

#include <boost/asio/dispatch.hpp>
#include <iostream>

#include "net/ContentSecurityPolicy.hpp"
#include "net/JsonResponses.hpp"
#include "net/PatientUploadRoute.hpp"
#include "net/ScanRoutes.hpp"

namespace orthosim::net {
namespace beast = boost::beast;
namespace websocket = beast::websocket;
namespace {

constexpr std::size_t kMaxDrainBytes = 1024 * 1024;
constexpr std::chrono::seconds kDrainTimeout{2};

// An error of an upload route: like jsonError, with the form field at fault ("body" for the
// request's body as a whole, "" when no field is at fault), as every reply of those routes has.
StringResponse uploadError(http::status status, std::string_view code, const std::string& message,
                           std::string_view path, std::string_view field, const ReplyTo& to) {
  return jsonResponse(status, {{"error", code}, {"message", message}, {"path", path}, {"field", field}}, to);
}

// The reply to a request the parser rejected, or nullopt when the connection just ended.
// `upload`: the path of an upload (a patient's, a scan's), which has its own body limit; empty for
// another request.
std::optional<StringResponse> parseErrorReply(beast::error_code ec, const HttpLimits& limits,
                                              const std::string& upload) {
  const ReplyTo to{11, false, false};
  auto reply = [&](http::status status, std::string_view code, const std::string& message) {
    return upload.empty() ? jsonError(status, code, message, "", to)
                          : uploadError(status, code, message, upload, "body", to);
  };
  if (ec == http::error::body_limit)
    return reply(http::status::payload_too_large, "body_too_large",
                 "request body over the limit of " +
                     (!upload.empty() ? std::to_string(limits.uploadBytes / (1024 * 1024)) + " MiB (--max-upload-mb)"
                                      : std::to_string(limits.bodyBytes) + " bytes"));
  if (ec == http::error::header_limit)
    return jsonError(http::status::request_header_fields_too_large, "header_too_large",
                     "request headers over the limit of " + std::to_string(limits.headerBytes) + " bytes", "", to);
  const bool parseError = &ec.category() == &http::make_error_code(http::error::bad_target).category();
  if (parseError && ec != http::error::partial_message)  // partial: the client left mid-request
    return reply(http::status::bad_request, "bad_request", "malformed HTTP request: " + ec.message());
  return std::nullopt;  // end of stream, timeout, reset: nobody to answer
}

// An access refusal (token, Host, Origin) of an upload, with the `field` every upload error has:
// "", no form field being at fault.
StringResponse withNoField(StringResponse reply) {
  nlohmann::json body = nlohmann::json::parse(reply.body(), nullptr, false);
  if (!body.is_object() || body.contains("field")) return reply;
  body["field"] = "";
  reply.body() = body.dump();
  reply.prepare_payload();
  return reply;
}

// The upload route `request` goes to; empty for another route.
std::string uploadPath(const Request& request) {
  return isPatientUpload(request) ? kPatientsPath : isScanUpload(request) ? kScansPath : "";
}

}  // namespace

HttpSession::HttpSession(boost::asio::ip::tcp::socket&& socket, std::shared_ptr<const ConnectionContext> context)
    : stream_(std::move(socket)), context_(std::move(context)), limits_(context_->limits) {}

void HttpSession::start() {
  // The socket was accepted on this session's strand; run on it from the start.
  boost::asio::dispatch(stream_.get_executor(),
                        beast::bind_front_handler(&HttpSession::readRequest, shared_from_this()));
}

void HttpSession::readRequest() {
  parser_.emplace();
  parser_->header_limit(static_cast<std::uint32_t>(limits_.headerBytes));
  // Beast checks a declared length against the limit while it parses the headers: allow the
  // upload's here, and hold every other route to its own once the headers say which it is.
  parser_->body_limit(std::max(limits_.bodyBytes, limits_.uploadBytes));
  stream_.expires_after(limits_.idleTimeout);
  http::async_read_header(stream_, buffer_, *parser_,
                          beast::bind_front_handler(&HttpSession::onHeader, shared_from_this()));
}

void HttpSession::onHeader(beast::error_code ec, std::size_t bytes) {
  if (ec) return onRead(ec, bytes);
  if (isPatientUpload(parser_->get()) || isScanUpload(parser_->get())) {
    if (std::optional<StringResponse> refusal = context_->router->refuseUpload(parser_->get()))
      return send(withNoField(std::move(*refusal)), true);
    return readUpload();
  }
  const boost::optional<std::uint64_t> length = parser_->content_length();
  if (length && *length > limits_.bodyBytes) return send(*parseErrorReply(http::error::body_limit, limits_, ""), true);
  parser_->body_limit(limits_.bodyBytes);  // a chunked body is counted as it comes
  http::async_read(stream_, buffer_, *parser_, beast::bind_front_handler(&HttpSession::onRead, shared_from_this()));
}

void HttpSession::readUpload() {
  const std::string path = uploadPath(parser_->get());
  const ReplyTo to{parser_->get().version(), false, false};
  std::shared_ptr<const void> slot = context_->uploads->tryTake();
  if (!slot) {
    StringResponse reply =
        uploadError(http::status::service_unavailable, "too_many_uploads",
                    "the server is receiving or importing " + std::to_string(context_->uploads->most()) +
                        " uploads, as many as it takes at once (--max-uploads); try again in a minute",
                    path, "", to);
    reply.set(http::field::retry_after, "30");
    return send(std::move(reply), true);
  }
  try {
    upload_ = std::make_shared<UploadBody>(context_->planning->options().dataDir / "imports", std::move(slot));
    uploadParser_.emplace(std::move(*parser_));
    uploadParser_->body_limit(limits_.uploadBytes);
    beast::error_code ec;
    uploadParser_->get().body().open(upload_->path().c_str(), beast::file_mode::write, ec);
    if (ec) throw beast::system_error(ec);
  } catch (const std::exception& e) {
    std::cerr << "orthosim serve: cannot store an upload's body in the data folder: " << e.what() << "\n";
    uploadParser_.reset();
    upload_.reset();
    return send(uploadError(http::status::internal_server_error, "import_failed",
                            "the server cannot store the upload in its data folder", path, "body", to),
                true);
  }
  stream_.expires_after(limits_.uploadTimeout);
  http::async_read(stream_, buffer_, *uploadParser_,
                   beast::bind_front_handler(&HttpSession::onUploadRead, shared_from_this()));
}

void HttpSession::onUploadRead(beast::error_code ec, std::size_t) {
  if (ec) {
    const std::string path = uploadPath(Request(uploadParser_->get().base()));
    uploadParser_.reset();
    upload_.reset();  // its file goes now, not when the connection does
    if (std::optional<StringResponse> reply = parseErrorReply(ec, limits_, path)) send(std::move(*reply), true);
    return;
  }
  uploadParser_->get().body().close();
  UploadRequest request{Request(std::move(uploadParser_->get().base())), std::move(upload_)};
  uploadParser_.reset();
  const bool keepAlive = request.head.keep_alive();
  auto self = shared_from_this();
  auto reply = [self, keepAlive](StringResponse response) {
    boost::asio::dispatch(self->stream_.get_executor(), [self, keepAlive, response = std::move(response)]() mutable {
      self->send(std::move(response), !keepAlive);
    });
  };
  if (isPatientUpload(request.head))
    net::importPatient(*context_->planning, std::move(request), std::move(reply));
  else
    net::stageScan(*context_->planning, std::move(request), std::move(reply));
}

void HttpSession::onRead(beast::error_code ec, std::size_t) {
  if (ec == http::error::end_of_stream) {
    beast::error_code ignored;
    stream_.socket().shutdown(boost::asio::ip::tcp::socket::shutdown_send, ignored);
    return;
  }
  if (ec) {
    // The request line is parsed first.
    if (std::optional<StringResponse> reply = parseErrorReply(ec, limits_, uploadPath(parser_->get())))
      send(std::move(*reply), true);
    return;  // otherwise the session ends here and its socket closes
  }
  if (websocket::is_upgrade(parser_->get())) return upgrade();
  if (isScanRoute(parser_->get())) return scanRequest();
  Response response = context_->router->handle(parser_->get());
  const bool closeAfter = std::visit([](const auto& r) { return r.need_eof(); }, response);
  send(std::move(response), closeAfter);
}

void HttpSession::scanRequest() {
  // The staged-scan routes change state like the upload: the same checks (Host, Origin, token).
  if (std::optional<StringResponse> refusal = context_->router->refuseUpload(parser_->get()))
    return send(std::move(*refusal), true);
  const bool keepAlive = parser_->get().keep_alive();
  auto self = shared_from_this();
  auto reply = [self, keepAlive](StringResponse response) {
    boost::asio::dispatch(self->stream_.get_executor(), [self, keepAlive, response = std::move(response)]() mutable {
      self->send(std::move(response), !keepAlive);
    });
  };
  net::scanRoute(*context_->planning, parser_->release(), std::move(reply));
}

void HttpSession::upgrade() {
  if (std::optional<StringResponse> refusal = context_->router->refuseUpgrade(parser_->get()))
    return send(std::move(*refusal), true);
  // A slot, free or given up by an idle connection without a case (session/SessionSlots).
  std::unique_ptr<server::SessionSlots::Slot> slot = context_->planning->slots().enter();
  if (!slot) {
    const ReplyTo to{parser_->get().version(), false, false};
    return send(jsonError(http::status::service_unavailable, "too_many_sessions",
                          "the server has as many planning sessions open as it allows; try again later", "/ws", to),
                true);
  }
  std::make_shared<WebSocketSession>(stream_.release_socket(), *context_->planning, context_->webSocket,
                                     std::move(slot))
      ->run(parser_->release());
}

void HttpSession::send(Response&& response, bool closeAfter) {
  response_ = std::move(response);
  stream_.expires_after(limits_.idleTimeout);
  std::visit(
      [&](auto& message) {
        // No page of another site may frame the planner (clickjacking) or sniff our types, and
        // the page runs no script but its own files.
        message.set(http::field::x_frame_options, "DENY");
        message.set("Content-Security-Policy", kContentSecurityPolicy);
        message.set("X-Content-Type-Options", "nosniff");
        http::async_write(stream_, message,
                          beast::bind_front_handler(&HttpSession::onWrite, shared_from_this(), closeAfter));
      },
      response_);
}

void HttpSession::onWrite(bool closeAfter, beast::error_code ec, std::size_t) {
  if (ec) return;
  if (closeAfter) return drainThenClose();
  response_ = StringResponse{};  // release an open file now rather than at the next write
  readRequest();
}

void HttpSession::drainThenClose() {
  beast::error_code ignored;
  stream_.socket().shutdown(boost::asio::ip::tcp::socket::shutdown_send, ignored);
  stream_.expires_after(kDrainTimeout);
  buffer_.consume(buffer_.size());
  stream_.async_read_some(buffer_.prepare(16 * 1024),
                          beast::bind_front_handler(&HttpSession::onDrain, shared_from_this()));
}

void HttpSession::onDrain(beast::error_code ec, std::size_t bytes) {
  drained_ += bytes;
  if (ec || drained_ > kMaxDrainBytes) return;  // client closed, timed out or sends too much: close
  stream_.async_read_some(buffer_.prepare(16 * 1024),
                          beast::bind_front_handler(&HttpSession::onDrain, shared_from_this()));
}

}  // namespace orthosim::net
