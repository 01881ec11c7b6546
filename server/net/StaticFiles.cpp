#include "net/StaticFiles.hpp"

#include "net/JsonResponses.hpp"
#include "net/MimeType.hpp"

namespace orthosim::net {

Response serveStaticFile(const WebRoot& web, std::string_view decodedPath, const ReplyTo& to) {
  const WebRoot::Lookup lookup = web.find(decodedPath);
  if (lookup.outcome == WebRoot::Outcome::Refused)
    return jsonError(http::status::bad_request, "bad_path", lookup.reason, decodedPath, to);
  if (lookup.outcome == WebRoot::Outcome::NotFound)
    return jsonError(http::status::not_found, "not_found", "no such file or route: " + std::string(decodedPath),
                     decodedPath, to);

  boost::beast::error_code ec;
  http::file_body::value_type file;
  file.open(lookup.file.c_str(), boost::beast::file_mode::scan, ec);
  if (ec)  // vanished or unreadable since the lookup
    return jsonError(http::status::not_found, "not_found", "cannot read " + std::string(decodedPath), decodedPath, to);
  const std::uint64_t size = file.size();
  const std::string type(mimeType(lookup.file));

  if (to.headOnly) {
    StringResponse head{http::status::ok, to.version};
    setCommonHeaders(head.base());
    head.set(http::field::content_type, type);
    head.content_length(size);
    head.keep_alive(to.keepAlive);
    return head;
  }
  FileResponse response{std::piecewise_construct, std::make_tuple(std::move(file)),
                        std::make_tuple(http::status::ok, to.version)};
  setCommonHeaders(response.base());
  response.set(http::field::content_type, type);
  response.content_length(size);
  response.keep_alive(to.keepAlive);
  return response;
}

}  // namespace orthosim::net
