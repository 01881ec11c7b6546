#pragma once
// An upload's body as the form parser reads it: the file the request was streamed into, read
// through a buffer of 1 MiB, so that a 200 MiB form is split into its parts without being held in
// memory.
#include <filesystem>
#include <string>
#include <vector>

#include "net/MultipartForm.hpp"

namespace orthosim::net {

class FormBodyFile : public FormBytes {
 public:
  // Throws std::runtime_error when the file cannot be opened.
  explicit FormBodyFile(const std::filesystem::path& file);
  ~FormBodyFile() override;
  FormBodyFile(const FormBodyFile&) = delete;
  FormBodyFile& operator=(const FormBodyFile&) = delete;

  std::uint64_t size() const override { return size_; }
  std::string read(std::uint64_t at, std::size_t n) override;
  std::uint64_t find(std::string_view needle, std::uint64_t from) override;

 private:
  int fd_ = -1;
  std::uint64_t size_ = 0;
  std::vector<char> buffer_;
};

}  // namespace orthosim::net
