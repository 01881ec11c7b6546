#pragma once
// The parts of a multipart/form-data body (RFC 7578), as a browser's FormData sends a form with
// files. Beast has no parser for it; the format is small: parts between "--BOUNDARY" lines, each
// with its own headers (Content-Disposition names the field and the file).
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace orthosim::net {

struct FormPart {
  std::string name;      // the form field
  std::string fileName;  // as the client sent it (maybe with a path); empty for a plain field
  std::string contentType;
  std::string data;
};

struct FormError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The boundary of a "multipart/form-data; boundary=..." content type; throws FormError when the
// type is another or has no boundary.
std::string formBoundary(std::string_view contentType);

// The parts of `body`, in order. Throws FormError naming what is malformed (a missing closing
// boundary, a part without headers or without a field name).
std::vector<FormPart> parseMultipartForm(std::string_view body, std::string_view boundary);

}  // namespace orthosim::net
