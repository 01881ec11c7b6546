#include "system/FolderInMessage.hpp"

namespace orthosim {

std::string withoutFolder(std::string message, std::string_view folder, std::string_view with) {
  if (folder.empty()) return message;
  for (std::size_t at = 0; (at = message.find(folder, at)) != std::string::npos; at += with.size())
    message.replace(at, folder.size(), with);
  return message;
}

}  // namespace orthosim
