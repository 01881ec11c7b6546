#pragma once
// Messages of libraries and of the engine name files by the paths they were read from: a staging or
// temporary folder the user never saw. Before such a message reaches a user, the folder is taken out
// (or replaced by words the user knows, "the scan"), leaving the file names the user gave.

#include <string>
#include <string_view>

namespace orthosim {

// Every occurrence of `folder` in `message` replaced by `with` (removed when `with` is empty).
std::string withoutFolder(std::string message, std::string_view folder, std::string_view with = "");

}  // namespace orthosim
