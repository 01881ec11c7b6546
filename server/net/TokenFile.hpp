#pragma once
// An access token kept in a file, so that a server started without one (the Docker image) still
// needs one: the first start writes a fresh random token there (readable by its owner only), the
// next starts read it back, and the operator copies it from there into the page's URL.
#include <filesystem>
#include <string>

namespace orthosim::net {

// The token in `file`, made (256 random bits, hex) when the file does not exist. Throws
// std::runtime_error naming the file when it cannot be read or written, or holds no token.
std::string loadOrCreateToken(const std::filesystem::path& file);

}  // namespace orthosim::net
