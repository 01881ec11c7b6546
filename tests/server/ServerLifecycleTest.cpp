// `orthosim serve` stops cleanly on SIGTERM and SIGINT, even with a client connected.
#include <gtest/gtest.h>

#include <boost/asio/ip/tcp.hpp>
#include <csignal>

#include "HttpTestClient.hpp"
#include "ServerProcess.hpp"

namespace orthosim {
namespace {

void expectCleanStop(int signal) {
  test::ServerProcess server;
  ASSERT_EQ(test::httpGet(server.port(), "/api/health").result(), boost::beast::http::status::ok);
  // An idle keep-alive connection must not hold the shutdown up.
  boost::asio::io_context io;
  boost::asio::ip::tcp::socket idle(io);
  idle.connect({boost::asio::ip::make_address("127.0.0.1"), server.port()});
  const std::optional<int> code = server.stop(signal, std::chrono::seconds(5));
  ASSERT_TRUE(code.has_value()) << "still running 5 s after signal " << signal;
  EXPECT_EQ(*code, 0);
}

TEST(ServerLifecycle, SigtermExitsZeroWithinFiveSeconds) { expectCleanStop(SIGTERM); }

TEST(ServerLifecycle, SigintExitsZeroWithinFiveSeconds) { expectCleanStop(SIGINT); }

TEST(ServerLifecycle, PortTakenIsAnError) {
  test::ServerProcess first;
  const std::string command =
      std::string(ORTHOSIM_CLI) + " serve --port " + std::to_string(first.port()) + " >/dev/null 2>&1";
  EXPECT_EQ(WEXITSTATUS(std::system(command.c_str())), 1);
}

}  // namespace
}  // namespace orthosim
