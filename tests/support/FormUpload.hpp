#pragma once
// Uploads as a browser's FormData sends them, for the server tests: the parts of a multipart form
// and the raw request that carries them (Connection: close), and a file's bytes to put in a part.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace orthosim::test {

struct Part {
  std::string field, fileName, data;  // fileName empty: a plain field
};

inline std::string readFile(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// POST `path` with `parts` as multipart/form-data; `extraHeaders` ("Name: value\r\n" each) go after
// the others.
inline std::string formRequest(const std::string& path, const std::vector<Part>& parts,
                               const std::string& extraHeaders = "") {
  const std::string boundary = "----orthosimTestBoundary7MA4YWxk";
  std::string body;
  for (const Part& p : parts) {
    body += "--" + boundary + "\r\nContent-Disposition: form-data; name=\"" + p.field + "\"";
    if (!p.fileName.empty()) body += "; filename=\"" + p.fileName + "\"\r\nContent-Type: application/octet-stream";
    body += "\r\n\r\n" + p.data + "\r\n";
  }
  body += "--" + boundary + "--\r\n";
  return "POST " + path +
         " HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\nContent-Type: multipart/form-data; boundary=" +
         boundary + "\r\nContent-Length: " + std::to_string(body.size()) + "\r\n" + extraHeaders + "\r\n" + body;
}

}  // namespace orthosim::test
