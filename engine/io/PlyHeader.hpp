#pragma once
// A PLY file's header, read before assimp reads the file: assimp allocates what the header declares
// ("element face 10000000") before it reads a byte of the data, so a few hundred bytes could make
// it take gigabytes. The counts are checked here against the bytes that follow the header.
#include <cstdint>
#include <istream>
#include <string>
#include <vector>

namespace orthosim {

struct PlyProperty {
  int bytes = 0;       // of a scalar, or of each item of a list
  int countBytes = 0;  // a list's count; 0 for a scalar
};

struct PlyElement {
  std::string name;  // vertex, face, ...
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

struct PlyHeader {
  enum class Format { Ascii, BinaryLittleEndian, BinaryBigEndian } format = Format::Ascii;
  std::uint64_t bytes = 0;  // the header's, up to and with the line "end_header"
  std::vector<PlyElement> elements;
};

// The header at the start of `in`. Throws std::runtime_error, its message starting with `name`, for
// a header that is not PLY, has no end_header within 64 KiB, or has an unknown type or line.
PlyHeader readPlyHeader(std::istream& in, const std::string& name);

// Refuses (std::runtime_error naming the file, the element, the count declared and the bytes
// present) a PLY whose elements cannot fit in the `size` bytes of the file: binary data is walked
// (each list's count read) to the exact size it needs; ASCII needs at least 2 bytes per value (a
// digit and a separator).
void checkPlySize(const std::string& path, std::uintmax_t size);

}  // namespace orthosim
