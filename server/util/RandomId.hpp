#pragma once
// Random identifiers that nobody can guess: session ids, export download ids, access tokens.
#include <string>

namespace orthosim::server {

// A random 128-bit identifier as 32 lowercase hex digits (std::random_device: /dev/urandom).
std::string randomHexId();

}  // namespace orthosim::server
