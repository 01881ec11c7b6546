#include "io/PlyHeader.hpp"

#include <charconv>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

namespace orthosim {
namespace {

constexpr std::uint64_t kMaxHeaderBytes = 64 * 1024;
constexpr std::uint64_t kUnbounded = std::numeric_limits<std::uint64_t>::max();

// Bytes of a PLY scalar type; 0 for a name that is none.
int typeBytes(const std::string& type) {
  static const std::map<std::string, int> sizes = {{"char", 1},  {"uchar", 1},   {"int8", 1},   {"uint8", 1},
                                                   {"short", 2}, {"ushort", 2},  {"int16", 2},  {"uint16", 2},
                                                   {"int", 4},   {"uint", 4},    {"int32", 4},  {"uint32", 4},
                                                   {"float", 4}, {"float32", 4}, {"double", 8}, {"float64", 8}};
  const auto it = sizes.find(type);
  return it == sizes.end() ? 0 : it->second;
}

bool isSigned(const std::string& type) {
  return type == "char" || type == "int8" || type == "short" || type == "int16" || type == "int" || type == "int32";
}

// a * b + c, or kUnbounded when it overflows.
std::uint64_t mulAdd(std::uint64_t a, std::uint64_t b, std::uint64_t c) {
  std::uint64_t product = 0, sum = 0;
  if (__builtin_mul_overflow(a, b, &product) || __builtin_add_overflow(product, c, &sum)) return kUnbounded;
  return sum;
}

std::string bytesText(std::uint64_t n) { return n == kUnbounded ? "more than 2^64" : std::to_string(n); }

// Reads the binary data from the file at any offset, through a window of it.
class DataWindow {
 public:
  explicit DataWindow(const std::string& path) : in_(path, std::ios::binary), buffer_(64 * 1024) {}
  // The `n` bytes (n <= 8) at `at`; false when the file ends before.
  bool read(std::uint64_t at, int n, unsigned char* out) {
    if (at < start_ || at + n > start_ + length_) {
      in_.clear();
      in_.seekg(static_cast<std::streamoff>(at));
      in_.read(reinterpret_cast<char*>(buffer_.data()), static_cast<std::streamsize>(buffer_.size()));
      start_ = at;
      length_ = static_cast<std::uint64_t>(in_.gcount());
      if (at + n > start_ + length_) return false;
    }
    for (int k = 0; k < n; ++k) out[k] = buffer_[at - start_ + k];
    return true;
  }

 private:
  std::ifstream in_;
  std::vector<unsigned char> buffer_;
  std::uint64_t start_ = 0, length_ = 0;
};

}  // namespace

PlyHeader readPlyHeader(std::istream& in, const std::string& name) {
  PlyHeader header;
  auto fail = [&](const std::string& why) -> void { throw std::runtime_error(name + ": PLY header: " + why); };
  std::string line;
  bool first = true, format = false;
  while (true) {
    if (!std::getline(in, line)) fail("no 'end_header' line (the header is cut off)");
    header.bytes += line.size() + (in.eof() ? 0 : 1);
    if (header.bytes > kMaxHeaderBytes) fail("no 'end_header' within the first 64 KiB");
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (first) {
      if (keyword != "ply") fail("the file does not start with 'ply'");
      first = false;
      continue;
    }
    if (keyword == "end_header") break;
    if (keyword == "format") {
      std::string kind;
      words >> kind;
      if (kind == "ascii")
        header.format = PlyHeader::Format::Ascii;
      else if (kind == "binary_little_endian")
        header.format = PlyHeader::Format::BinaryLittleEndian;
      else if (kind == "binary_big_endian")
        header.format = PlyHeader::Format::BinaryBigEndian;
      else
        fail("unknown format '" + kind + "'");
      format = true;
    } else if (keyword == "element") {
      PlyElement element;
      std::string count;
      words >> element.name >> count;
      const auto [end, ec] = std::from_chars(count.data(), count.data() + count.size(), element.count);
      if (element.name.empty() || count.empty() || ec != std::errc() || end != count.data() + count.size())
        fail("'" + line + "' is not 'element NAME COUNT' with a whole number COUNT");
      header.elements.push_back(element);
    } else if (keyword == "property") {
      if (header.elements.empty()) fail("a property before any element");
      std::string type;
      words >> type;
      PlyProperty property;
      if (type == "list") {
        std::string countType, itemType;
        words >> countType >> itemType;
        property.countBytes = typeBytes(countType);
        property.bytes = typeBytes(itemType);
        // A list's count is a whole number: a float count would make no sense to any reader.
        if (property.countBytes == 0 || countType.find("float") != std::string::npos || countType == "double")
          fail("'" + line + "': unknown list count type '" + countType + "'");
        if (property.bytes == 0) fail("'" + line + "': unknown type '" + itemType + "'");
        property.countBytes = isSigned(countType) ? -property.countBytes : property.countBytes;
      } else {
        property.bytes = typeBytes(type);
        if (property.bytes == 0) fail("'" + line + "': unknown type '" + type + "'");
      }
      header.elements.back().properties.push_back(property);
    }  // comment, obj_info and other lines declare no data
  }
  if (!format) fail("no 'format' line");
  return header;
}

void checkPlySize(const std::string& path, std::uintmax_t size) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot open file");
  const PlyHeader header = readPlyHeader(in, path);
  const std::uint64_t present = size > header.bytes ? size - header.bytes : 0;
  const bool ascii = header.format == PlyHeader::Format::Ascii;
  auto refuse = [&](const PlyElement& e, std::uint64_t needed) {
    throw std::runtime_error(path + ": the PLY header declares " + std::to_string(e.count) + " '" + e.name +
                             "' elements, which need at least " + bytesText(needed) + " bytes (with those before); " +
                             "the file has " + std::to_string(present) + " bytes after its header");
  };
  // The least each element can take: fixed-size values exactly, a list its count and no item; in
  // ASCII 2 bytes a value (the last one may have no separator after it).
  std::uint64_t needed = 0;
  for (const PlyElement& e : header.elements) {
    std::uint64_t least = 0;
    for (const PlyProperty& p : e.properties)
      least += ascii ? 2 : static_cast<std::uint64_t>(p.countBytes != 0 ? std::abs(p.countBytes) : p.bytes);
    needed = mulAdd(e.count, least, needed);
    if (needed > (ascii ? present + 1 : present)) refuse(e, needed);
  }
  if (ascii) return;
  // Binary lists: walk their counts to the exact size, so that a file cut short is refused here.
  DataWindow data(path);
  const bool little = header.format == PlyHeader::Format::BinaryLittleEndian;
  std::uint64_t at = header.bytes;
  for (const PlyElement& e : header.elements) {
    bool lists = false;
    std::uint64_t fixed = 0;
    for (const PlyProperty& p : e.properties) {
      lists = lists || p.countBytes != 0;
      fixed += static_cast<std::uint64_t>(p.bytes);
    }
    if (!lists) {
      at = mulAdd(e.count, fixed, at);
      if (at > size) refuse(e, at - header.bytes);
      continue;
    }
    for (std::uint64_t i = 0; i < e.count; ++i)
      for (const PlyProperty& p : e.properties) {
        if (p.countBytes == 0) {
          at += static_cast<std::uint64_t>(p.bytes);
          if (at > size) refuse(e, at - header.bytes);
          continue;
        }
        const int n = std::abs(p.countBytes);
        unsigned char raw[8] = {};
        if (!data.read(at, n, raw)) refuse(e, at + n - header.bytes);
        std::uint64_t items = 0;
        for (int k = 0; k < n; ++k) items = (items << 8) | raw[little ? n - 1 - k : k];
        if (p.countBytes < 0 && (raw[little ? n - 1 : 0] & 0x80))
          throw std::runtime_error(path + ": PLY element '" + e.name + "' " + std::to_string(i) +
                                   " has a list with a negative count");
        at = mulAdd(items, static_cast<std::uint64_t>(p.bytes), at + static_cast<std::uint64_t>(n));
        if (at > size) refuse(e, at - header.bytes);
      }
  }
}

}  // namespace orthosim
