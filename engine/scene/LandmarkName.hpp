#pragma once
// A landmark's name: 1-64 letters, digits, '_' or '-'. Names come from users' files and reach the
// page, so one rule refuses anything else (markup, quotes, spaces, control characters) where they
// enter: at import and when a landmark is placed.
#include <string>

namespace orthosim {

inline bool isLandmarkName(const std::string& s) {
  if (s.empty() || s.size() > 64) return false;
  for (const char c : s)
    if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-'))
      return false;
  return true;
}

}  // namespace orthosim
