// docker/compose.yaml (Redis, the server with --redis, two workers, nginx) cannot be run here (no
// Docker engine), so it is checked against what it runs: the server's command is the image's
// (docker/Dockerfile CMD) with --redis; every orthosim command line is accepted by the real binary
// (run with the image's paths mapped to this tree's, it gets as far as connecting to Redis); the
// shared volume is mounted where the image keeps its state; nginx's configuration reaches the
// server service and takes uploads as large as the server does.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>

namespace orthosim::test {
namespace {
namespace fs = std::filesystem;
using nlohmann::json;

std::string source(const std::string& path) {
  std::ifstream in(std::string(ORTHOSIM_SOURCE_DIR) + "/" + path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Each service's lines of docker/compose.yaml (the two-space-indented keys under "services:").
std::map<std::string, std::string> services() {
  std::istringstream in(source("docker/compose.yaml"));
  std::map<std::string, std::string> found;
  std::string line, current;
  bool inServices = false;
  const std::regex service("^  ([a-z][a-z0-9-]*):\\s*$");
  std::smatch m;
  while (std::getline(in, line)) {
    if (!line.empty() && line[0] != ' ' && line[0] != '#') inServices = line == "services:";
    if (!inServices) continue;
    if (std::regex_match(line, m, service))
      current = m[1];
    else if (!current.empty())
      found[current] += line + "\n";
  }
  return found;
}

// The `command:` of a service: one line, a JSON array (YAML's flow sequence of quoted strings).
std::vector<std::string> command(const std::string& serviceLines) {
  std::smatch m;
  if (!std::regex_search(serviceLines, m, std::regex("\n?    command: (\\[.*\\])\n"))) return {};
  return json::parse(m[1].str()).get<std::vector<std::string>>();
}

std::vector<std::string> imageCommand() {
  std::istringstream in(source("docker/Dockerfile"));
  std::string line, cmd;
  while (std::getline(in, line))
    if (line.rfind("CMD ", 0) == 0) cmd = line.substr(4);
  return json::parse(cmd).get<std::vector<std::string>>();
}

// Runs the built orthosim with `args` (the image's paths replaced by `data` and this tree's web
// page and cases, Redis by a closed port); its exit status and output.
std::pair<int, std::string> run(std::vector<std::string> args, const fs::path& data) {
  std::string cmd = "timeout 60 " + std::string(ORTHOSIM_CLI);
  for (std::string a : std::vector<std::string>(args.begin() + 1, args.end())) {
    if (a.rfind("/var/lib/orthosim", 0) == 0) a = data.string() + a.substr(17);
    if (a == "/opt/orthosim/web") a = std::string(ORTHOSIM_SOURCE_DIR) + "/web";
    if (a == "/opt/orthosim/cases") a = std::string(ORTHOSIM_SOURCE_DIR) + "/cases";
    if (a == "redis://redis:6379") a = "redis://127.0.0.1:1";  // nothing listens there
    if (a == "8080") a = "0";
    cmd += " '" + a + "'";
  }
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen((cmd + " 2>&1").c_str(), "r"), pclose);
  std::string out;
  char buf[4096];
  for (size_t n; (n = fread(buf, 1, sizeof buf, pipe.get())) > 0;) out.append(buf, n);
  const int status = pclose(pipe.release());
  return {WEXITSTATUS(status), out};
}

TEST(ComposeFile, HasRedisAServerWithRedisTwoWorkersAndNginx) {
  const std::map<std::string, std::string> s = services();
  for (const char* name : {"redis", "server", "worker", "nginx"}) ASSERT_TRUE(s.count(name)) << "no service " << name;
  std::vector<std::string> expected = imageCommand();
  expected.insert(expected.end(), {"--redis", "redis://redis:6379"});
  EXPECT_EQ(command(s.at("server")), expected) << "the image's CMD (token file included) with --redis";
  const std::vector<std::string> worker = command(s.at("worker"));
  ASSERT_GE(worker.size(), 2u);
  EXPECT_EQ(worker[1], "worker");
  auto has = [](const std::vector<std::string>& c, const std::string& option, const std::string& value) {
    for (size_t i = 0; i + 1 < c.size(); ++i)
      if (c[i] == option && c[i + 1] == value) return true;
    return false;
  };
  EXPECT_TRUE(has(worker, "--redis", "redis://redis:6379"));
  EXPECT_TRUE(has(worker, "--data", "/var/lib/orthosim")) << "the server's data folder";
  EXPECT_TRUE(has(worker, "--builtin-cases", "/opt/orthosim/cases")) << "the server's built-in cases";
  EXPECT_NE(s.at("worker").find("replicas: 2"), std::string::npos);
  EXPECT_EQ(command(s.at("redis")).at(0), "redis-server");
  // The one volume, where the image keeps its state; every service with healthcheck and restart.
  EXPECT_NE(source("docker/Dockerfile").find("VOLUME /var/lib/orthosim"), std::string::npos);
  EXPECT_NE(source("docker/Dockerfile").find("COPY cases/ /opt/orthosim/cases/"), std::string::npos);
  for (const char* name : {"server", "worker"})
    EXPECT_NE((s.at(name) + source("docker/compose.yaml")).find("- orthosim-data:/var/lib/orthosim"),
              std::string::npos);
  for (const auto& [name, lines] : s) {
    EXPECT_NE(lines.find("healthcheck:"), std::string::npos) << name;
    EXPECT_TRUE(lines.find("restart: unless-stopped") != std::string::npos ||
                lines.find("<<: *orthosim") != std::string::npos)
        << name;
  }
}

TEST(ComposeFile, TheBinaryAcceptsEveryOrthosimCommandLine) {
  const fs::path data = fs::temp_directory_path() / ("orthosim_compose_" + std::to_string(::getpid()));
  fs::remove_all(data);
  fs::create_directories(data);
  for (const auto& [name, lines] : services()) {
    const std::vector<std::string> c = command(lines);
    if (c.empty() || c[0] != "orthosim") continue;
    const auto [status, out] = run(c, data);
    // Every option parsed and every path found: it stops only at Redis, which is not there.
    EXPECT_EQ(status, 1) << name << ": " << out;
    EXPECT_NE(out.find("orthosim " + c[1] + ": Redis at redis://127.0.0.1:1 cannot be reached"), std::string::npos)
        << name << ": " << out;
    EXPECT_EQ(out.find("no ArtiSynth face in"), std::string::npos) << name << ": the built-in cases' path: " << out;
  }
  fs::remove_all(data);
}

TEST(ComposeFile, NginxReachesTheServerServiceStickilyWithTheServersUploadLimit) {
  const std::string conf = source("docker/nginx.conf");
  const std::string nginx = services().at("nginx");
  EXPECT_NE(nginx.find("./nginx.conf:/etc/nginx/nginx.conf"), std::string::npos) << "compose mounts docker/nginx.conf";
  EXPECT_NE(conf.find("server server:8080;"), std::string::npos) << "the server service's port";
  EXPECT_TRUE(std::regex_search(conf, std::regex("hash \\$\\w+ consistent;"))) << "sticky sessions";
  EXPECT_NE(conf.find("proxy_set_header Upgrade $http_upgrade;"), std::string::npos) << "WebSocket";
  EXPECT_NE(conf.find("proxy_read_timeout"), std::string::npos);
  // The server's default --max-upload-mb (cli/Commands.hpp ServeOptions::maxUploadMb).
  std::smatch m;
  const std::string options = source("server/cli/Commands.hpp");
  ASSERT_TRUE(std::regex_search(options, m, std::regex("int maxUploadMb = (\\d+);")));
  EXPECT_NE(conf.find("client_max_body_size " + m[1].str() + "m;"), std::string::npos);
}

}  // namespace
}  // namespace orthosim::test
