#pragma once
// The parts of a multipart/form-data body (RFC 7578), as a browser's FormData sends a form with
// files. Beast has no parser for it; the format is small: parts between "--BOUNDARY" lines, each
// with its own headers (Content-Disposition names the field and the file). An upload's body is on
// disk (net/FormBodyFile): its parts are located, not copied.
#include <cstdint>
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

// Where a part's bytes lie in the body.
struct FormPartSpan {
  std::string name;
  std::string fileName;
  std::string contentType;
  std::uint64_t offset = 0;
  std::uint64_t size = 0;
};

// A body's bytes as the parser reads them: a string in memory, or a file (net/FormBodyFile).
class FormBytes {
 public:
  static constexpr std::uint64_t npos = ~std::uint64_t(0);
  virtual ~FormBytes() = default;
  virtual std::uint64_t size() const = 0;
  // Up to `n` bytes from `at`; fewer at the end.
  virtual std::string read(std::uint64_t at, std::size_t n) = 0;
  // Where `needle` first starts at or after `from`; npos when nowhere.
  virtual std::uint64_t find(std::string_view needle, std::uint64_t from) = 0;
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

// The same, each part's bytes located in `body` rather than copied. A part's headers may take at
// most 16 KiB.
std::vector<FormPartSpan> locateFormParts(FormBytes& body, std::string_view boundary);

}  // namespace orthosim::net
