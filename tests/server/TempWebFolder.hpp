#pragma once
// A scratch web folder for one test, removed afterwards, with a secret file beside it (outside
// the folder) that no request may reach.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace orthosim::test {

struct TempWebFolder {
  std::filesystem::path base, web, secret;

  explicit TempWebFolder(const std::string& name) {
    base = std::filesystem::temp_directory_path() / ("orthosim_" + name + "_" + std::to_string(::getpid()));
    std::filesystem::remove_all(base);
    web = base / "web";
    std::filesystem::create_directories(web);
    secret = base / "secret.txt";
    write("../secret.txt", "SECRET");
  }
  ~TempWebFolder() { std::filesystem::remove_all(base); }

  // Writes `content` to web/relative (creating folders).
  void write(const std::string& relative, const std::string& content) const {
    const std::filesystem::path path = web / relative;
    std::filesystem::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary) << content;
  }
};

}  // namespace orthosim::test
