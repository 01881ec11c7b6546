// What a client is told when the server fails names the user's files, never the server's folders
// (the log keeps those): a case whose skin file went missing fails to open with the file's name.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "ServerProcess.hpp"
#include "WsTestClient.hpp"
#include "phantom/PhantomCase.hpp"

namespace orthosim {
namespace {
namespace fs = std::filesystem;
using nlohmann::json;
using namespace std::chrono_literals;

TEST(ClientMessages, AFailedOpeningNamesTheFileNotTheServersFolder) {
  const fs::path root = fs::temp_directory_path() / ("orthosim_client_messages_" + std::to_string(::getpid()));
  fs::remove_all(root);
  writePhantomCase(0, (root / "cases" / "broken").string());
  fs::remove(root / "cases" / "broken" / "skin.obj");
  {
    test::ServerProcess server(
        {"--data", (root / "data").string(), "--cases", (root / "cases").string(), "--no-warm-up"});
    test::WsTestClient ws(server.port());
    ws.send({{"type", "open"}, {"case", "broken"}});
    const json failed = ws.waitFor("error", 120s);
    EXPECT_EQ(failed["error"], "open_failed") << failed.dump();
    const std::string message = failed["message"];
    EXPECT_NE(message.find("skin.obj"), std::string::npos) << message;
    EXPECT_EQ(message.find(root.string()), std::string::npos) << message;
    EXPECT_EQ(message.find(fs::temp_directory_path().string() + "/"), std::string::npos) << message;
  }
  fs::remove_all(root);
}

}  // namespace
}  // namespace orthosim
