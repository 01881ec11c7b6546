// The image's command binds every interface (a container is reached through its published port),
// so it must not serve without a token: it names a token file (made on first start) or a token.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>

namespace orthosim::test {
namespace {

std::string imageCommand() {
  std::ifstream in(std::string(ORTHOSIM_SOURCE_DIR) + "/docker/Dockerfile");
  std::string line, cmd;
  while (std::getline(in, line))
    if (line.rfind("CMD ", 0) == 0) cmd = line;  // the last CMD is the image's
  return cmd;
}

TEST(DockerImage, ServesEveryInterfaceOnlyWithAToken) {
  const std::string cmd = imageCommand();
  ASSERT_FALSE(cmd.empty()) << "docker/Dockerfile has no CMD";
  ASSERT_NE(cmd.find("\"serve\""), std::string::npos) << cmd;
  ASSERT_NE(cmd.find("\"0.0.0.0\""), std::string::npos) << "the container must listen beyond its own loopback: " << cmd;
  EXPECT_TRUE(std::regex_search(cmd, std::regex("\"--token-file\", \"/var/lib/orthosim/[^\"]+\"")) ||
              cmd.find("\"--token\"") != std::string::npos)
      << "bound to 0.0.0.0 without --token-file or --token: " << cmd;
  EXPECT_EQ(cmd.find("--insecure"), std::string::npos) << cmd;
}

}  // namespace
}  // namespace orthosim::test
