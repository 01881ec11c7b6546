#include "util/ClientText.hpp"

#include <filesystem>
#include <set>
#include <string_view>

namespace orthosim::server {
namespace {

bool startsWord(const std::string& text, std::size_t at) {
  if (at == 0) return true;
  const char before = text[at - 1];
  return before == ' ' || before == '\'' || before == '"' || before == '(' || before == '=' || before == '[' ||
         before == ',' || before == '\n' || before == '\t';
}

bool endsPath(char c) {
  return c == ' ' || c == '\'' || c == '"' || c == ':' || c == ',' || c == ';' || c == ')' || c == ']' || c == '\n' ||
         c == '\t';
}

// The machine's top-level folders, read once: a reply is checked word by word, and asking the file
// system for every slash-word of every reply would cost a system call each.
const std::set<std::string, std::less<>>& topLevelFolders() {
  static const std::set<std::string, std::less<>> folders = [] {
    std::set<std::string, std::less<>> names;
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator("/", ec))
      if (entry.is_directory(ec)) names.insert(entry.path().filename().string());
    return names;
  }();
  return folders;
}

// "/srv/data/x.json" -> true when /srv is a folder of this machine and the path has two parts or more.
bool isMachinePath(std::string_view path) {
  const std::size_t second = path.find('/', 1);
  if (second == std::string_view::npos || second == 1 || second + 1 >= path.size()) return false;
  return topLevelFolders().count(path.substr(1, second - 1)) > 0;
}

std::string_view lastPart(std::string_view path) {
  while (path.size() > 1 && path.back() == '/') path.remove_suffix(1);
  return path.substr(path.rfind('/') + 1);
}

}  // namespace

std::string withoutServerPaths(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  std::size_t i = 0;
  while (i < text.size()) {
    if (text[i] != '/' || !startsWord(text, i)) {
      out += text[i++];
      continue;
    }
    std::size_t end = i;
    while (end < text.size() && !endsPath(text[end])) ++end;
    const std::string_view path(text.data() + i, end - i);
    if (isMachinePath(path))
      out += lastPart(path);
    else
      out += path;
    i = end;
  }
  return out;
}

std::string jsonSyntaxMessage(const nlohmann::json::exception& error) {
  std::string what = error.what();
  if (what.rfind("[json.exception.", 0) == 0) {
    const std::size_t tagEnd = what.find("] ");
    if (tagEnd != std::string::npos) what.erase(0, tagEnd + 2);
  }
  if (what.rfind("parse error ", 0) == 0) what.erase(0, 12);  // "at line 1, column 21: ..."
  return what;
}

}  // namespace orthosim::server
