#include "net/Server.hpp"

#include <unistd.h>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/signal_set.hpp>

#include <algorithm>
#include <csignal>
#include <stdexcept>
#include <thread>
#include <vector>

#include "net/BindRule.hpp"
#include "net/Listener.hpp"
#include "net/Router.hpp"

namespace orthosim::net {
using boost::asio::ip::tcp;

struct Server::Impl {
  ServerOptions options;
  server::PlanningService planning;  // declared first: outlives the sessions the io_context holds
  boost::asio::io_context io;
  boost::asio::signal_set signals{io, SIGINT, SIGTERM};
  std::shared_ptr<Listener> listener;
  int stopSignal = 0;

  explicit Impl(const ServerOptions& o) : options(o), planning(o.planning), io(std::max(1, o.networkThreads)) {}
};

namespace {

tcp::endpoint resolveEndpoint(boost::asio::io_context& io, const std::string& host, unsigned short port) {
  boost::system::error_code ec;
  tcp::resolver resolver(io);
  // Numeric addresses and names such as "localhost"; the first result is used.
  const auto results = resolver.resolve(host, std::to_string(port), tcp::resolver::passive, ec);
  if (ec || results.empty()) throw std::runtime_error("cannot resolve host '" + host + "': " + ec.message());
  return results.begin()->endpoint();
}

// The names other machines may use for this one (its host name), when they can reach it at all.
std::vector<std::string> machineNames(const boost::asio::ip::address& bound) {
  if (bound.is_loopback()) return {};
  char name[256] = {};
  if (::gethostname(name, sizeof name - 1) != 0 || !*name) return {};
  return {name};
}

}  // namespace

Server::Server(const ServerOptions& options) : impl_(std::make_unique<Impl>(options)) {
  const tcp::endpoint endpoint = resolveEndpoint(impl_->io, options.host, options.port);
  if (std::optional<std::string> why = bindRefusal(endpoint.address(), options.access.token, options.insecure))
    throw std::runtime_error(*why);
  const std::string bound =
      endpoint.address().is_v6() ? "[" + endpoint.address().to_string() + "]" : endpoint.address().to_string();
  auto context = std::make_shared<ConnectionContext>();
  context->router =
      std::make_shared<const Router>(WebRoot(options.webDir), ApiRoutes(impl_->planning),
                                     AccessPolicy(options.access, bound, machineNames(endpoint.address())));
  context->planning = &impl_->planning;
  context->limits = options.limits;
  context->uploads = std::make_shared<UploadSlots>(options.limits.maxUploads);
  context->webSocket = options.webSocket;
  impl_->listener = std::make_shared<Listener>(impl_->io, endpoint, std::move(context));
  impl_->listener->start();
  if (!options.warmUpCase.empty()) impl_->planning.warmUp(options.warmUpCase);
  impl_->signals.async_wait([impl = impl_.get()](const boost::system::error_code& ec, int signal) {
    if (ec) return;
    impl->stopSignal = signal;
    impl->io.stop();  // abandons open connections; their sessions are destroyed with the io_context
  });
}

Server::~Server() = default;

std::string Server::host() const {
  const auto address = impl_->listener->endpoint().address();
  return address.is_v6() ? "[" + address.to_string() + "]" : address.to_string();
}

unsigned short Server::port() const { return impl_->listener->endpoint().port(); }

void Server::stop() {
  boost::asio::post(impl_->io, [impl = impl_.get()] { impl->io.stop(); });
}

int Server::runUntilSignal() {
  std::vector<std::thread> threads;
  for (int i = 1; i < impl_->options.networkThreads; ++i) threads.emplace_back([this] { impl_->io.run(); });
  impl_->io.run();  // the calling thread is the first network thread
  for (std::thread& t : threads) t.join();
  impl_->planning.shutdown();  // cancels fine jobs; saved plans were written whole when saved
  return impl_->stopSignal;
}

}  // namespace orthosim::net
