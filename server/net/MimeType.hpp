#pragma once
// Content-Type of a static file, from its extension (case-insensitive).
#include <filesystem>
#include <string_view>

namespace orthosim::net {

// html, js, mjs, css, json, png, jpg/jpeg, svg, ico, txt, wasm; anything else is served as
// application/octet-stream so that a browser never guesses (and never runs) it.
std::string_view mimeType(const std::filesystem::path& file);

}  // namespace orthosim::net
