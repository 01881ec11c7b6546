#include "net/UploadBody.hpp"

#include "system/TemporaryName.hpp"

namespace orthosim::net {

UploadBody::UploadBody(const std::filesystem::path& folder, std::shared_ptr<const void> slot)
    : path_(folder / ("body-" + temporarySuffix())), slot_(std::move(slot)) {
  std::filesystem::create_directories(folder);
}

UploadBody::~UploadBody() {
  std::error_code ignored;
  std::filesystem::remove(path_, ignored);
}

}  // namespace orthosim::net
