#pragma once
// JSON replies. Every error the HTTP API sends has the same shape, which the WebSocket protocol
// reuses: {"error": CODE, "message": TEXT, "path": PATH} (docs/protocol.md).
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "net/HttpMessages.hpp"

namespace orthosim::net {

StringResponse jsonResponse(http::status status, const nlohmann::json& body, const ReplyTo& to);

// code: a short stable identifier ("not_found", "bad_request", ...); message: for a human.
StringResponse jsonError(http::status status, std::string_view code, const std::string& message, std::string_view path,
                         const ReplyTo& to);

// Headers every response carries (server name, no MIME sniffing).
void setCommonHeaders(http::response_header<>& header);

}  // namespace orthosim::net
