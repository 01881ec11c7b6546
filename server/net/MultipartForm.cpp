#include "net/MultipartForm.hpp"

#include <algorithm>
#include <cctype>

namespace orthosim::net {
namespace {

std::string lower(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(), [](unsigned char c) { return std::tolower(c); });
  return out;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

// The value of `key` in a header's parameters (`form-data; name="skin"; filename="a.stl"`); quoted
// values may hold ';'. Empty when absent.
std::string parameter(std::string_view header, std::string_view key) {
  const std::string lowered = lower(header);
  for (std::size_t at = lowered.find(';'); at != std::string::npos; at = lowered.find(';', at + 1)) {
    std::size_t p = at + 1;
    while (p < lowered.size() && lowered[p] == ' ') ++p;
    if (lowered.compare(p, key.size(), key) != 0 || p + key.size() >= lowered.size() || lowered[p + key.size()] != '=')
      continue;
    p += key.size() + 1;
    if (p < header.size() && header[p] == '"') {
      std::string value;
      for (++p; p < header.size() && header[p] != '"'; ++p) {
        if (header[p] == '\\' && p + 1 < header.size()) ++p;
        value += header[p];
      }
      return value;
    }
    const std::size_t end = header.find(';', p);
    return std::string(trim(header.substr(p, end == std::string::npos ? std::string::npos : end - p)));
  }
  return {};
}

constexpr std::size_t kMaxPartHeaders = 16 * 1024;

// The part from `start` to `end` (the CRLF before the next delimiter).
FormPartSpan locatePart(FormBytes& body, std::uint64_t start, std::uint64_t end, std::size_t index) {
  const std::string head =
      body.read(start, static_cast<std::size_t>(std::min<std::uint64_t>(end - start, kMaxPartHeaders)));
  const std::size_t headersEnd = head.find("\r\n\r\n");
  const std::string where = "form part " + std::to_string(index + 1);
  if (headersEnd == std::string::npos)
    throw FormError(where + (head.size() == kMaxPartHeaders ? " has headers longer than 16 KiB"
                                                            : " has no blank line after its headers"));
  FormPartSpan p;
  std::string_view headers = std::string_view(head).substr(0, headersEnd);
  while (!headers.empty()) {
    const std::size_t eol = headers.find("\r\n");
    const std::string_view line = headers.substr(0, eol);
    headers = eol == std::string_view::npos ? std::string_view{} : headers.substr(eol + 2);
    const std::size_t colon = line.find(':');
    if (colon == std::string_view::npos) throw FormError(where + ": malformed header line");
    const std::string key = lower(trim(line.substr(0, colon)));
    const std::string_view value = trim(line.substr(colon + 1));
    if (key == "content-disposition") {
      if (lower(value).rfind("form-data", 0) != 0) throw FormError(where + ": Content-Disposition is not form-data");
      p.name = parameter(value, "name");
      p.fileName = parameter(value, "filename");
    } else if (key == "content-type") {
      p.contentType = std::string(value);
    }
  }
  if (p.name.empty()) throw FormError(where + " has no field name (Content-Disposition: form-data; name=...)");
  p.offset = start + headersEnd + 4;
  p.size = end - p.offset;
  return p;
}

// A body held in memory.
class StringBytes : public FormBytes {
 public:
  explicit StringBytes(std::string_view body) : body_(body) {}
  std::uint64_t size() const override { return body_.size(); }
  std::string read(std::uint64_t at, std::size_t n) override {
    return at >= body_.size() ? std::string() : std::string(body_.substr(static_cast<std::size_t>(at), n));
  }
  std::uint64_t find(std::string_view needle, std::uint64_t from) override {
    const std::size_t at = from > body_.size() ? std::string_view::npos : body_.find(needle, from);
    return at == std::string_view::npos ? npos : at;
  }

 private:
  std::string_view body_;
};

}  // namespace

std::string formBoundary(std::string_view contentType) {
  if (lower(trim(contentType)).rfind("multipart/form-data", 0) != 0)
    throw FormError("Content-Type must be multipart/form-data (a form with files), not '" + std::string(contentType) +
                    "'");
  std::string boundary = parameter(contentType, "boundary");
  if (boundary.empty() || boundary.size() > 70)
    throw FormError("Content-Type multipart/form-data needs a boundary of 1-70 characters");
  return boundary;
}

std::vector<FormPartSpan> locateFormParts(FormBytes& body, std::string_view boundary) {
  const std::string delimiter = "--" + std::string(boundary);
  const std::string separator = "\r\n" + delimiter;
  // The first delimiter may open the body directly (no preamble), so search from a virtual CRLF.
  const bool opens = body.read(0, delimiter.size()) == delimiter;
  std::uint64_t at = opens ? 0 : body.find(separator, 0);
  if (at == FormBytes::npos) throw FormError("the form body has no part (no '" + delimiter + "' line)");
  at += opens ? delimiter.size() : separator.size();
  std::vector<FormPartSpan> parts;
  for (;;) {
    const std::string next2 = body.read(at, 2);
    if (next2 == "--") return parts;  // the closing delimiter
    if (next2 != "\r\n") throw FormError("form delimiter line not ended by CRLF");
    at += 2;
    const std::uint64_t next = body.find(separator, at);
    if (next == FormBytes::npos)
      throw FormError("the form body ends inside part " + std::to_string(parts.size() + 1) +
                      " (no closing boundary: was the upload cut off?)");
    parts.push_back(locatePart(body, at, next, parts.size()));
    at = next + separator.size();
  }
}

std::vector<FormPart> parseMultipartForm(std::string_view body, std::string_view boundary) {
  StringBytes bytes(body);
  std::vector<FormPart> parts;
  for (const FormPartSpan& span : locateFormParts(bytes, boundary))
    parts.push_back(
        {span.name, span.fileName, span.contentType,
         std::string(body.substr(static_cast<std::size_t>(span.offset), static_cast<std::size_t>(span.size)))});
  return parts;
}

}  // namespace orthosim::net
