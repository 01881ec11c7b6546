#pragma once
// What a client may be told when something fails: the reason in plain words, without the server's
// folders (the log keeps them) or a library's internal tags. Messages may carry text a client sent
// or a file held (any bytes); the JSON writers replace invalid UTF-8 when they send them.
#include <string>

#include <nlohmann/json.hpp>

namespace orthosim::server {

// Every absolute path of this machine in `text` (a "/" word whose first folder exists here, such as
// /srv/data/patients/p1/case.json) shortened to its last part (case.json). JSON pointers such as
// /poses/maxilla are left alone.
std::string withoutServerPaths(const std::string& text);

// A JSON syntax error as a client reads it: "at byte 21: syntax error while parsing object -
// invalid literal; last read: '...'", without nlohmann's "[json.exception.parse_error.101]".
std::string jsonSyntaxMessage(const nlohmann::json::exception& error);

}  // namespace orthosim::server
