#pragma once
// The names a client may give: case folders and saved plans. They become file names, so the rule
// lives with the cases, not with the session protocol that also checks them.
#include <string>

namespace orthosim::server {

// Case and plan names: 1-64 of [A-Za-z0-9_-], starting with a letter or digit. They become file
// names, so nothing else (no '.', '/', spaces) is ever accepted.
bool isIdentifier(const std::string& s);

}  // namespace orthosim::server
