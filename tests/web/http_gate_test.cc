// The monitor under floods, over real loopback sockets: a client that
// opens many event streams, one that trickles its requests (slowloris) and
// one that posts without a length must not stop /healthz or a page from
// answering within a second; past the caps connections are told so (429,
// 503, 408, 411) instead of waiting. Each flood is bounded in count and
// time (a few seconds).
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <httplib.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

#include "tests/testing/scratch_dir.h"
#include "web/monitor_server.h"

namespace wavebake::web {
namespace {

using Clock = std::chrono::steady_clock;
constexpr char kFloodToken[] = "flood-token";

// A connected loopback socket, closed with the object.
class Conn {
 public:
  explicit Conn(int port) : fd_(::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0)) {
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(static_cast<uint16_t>(port));
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    ok_ = ::connect(fd_, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0;
  }
  ~Conn() { ::close(fd_); }
  Conn(const Conn&) = delete;
  bool ok() const { return ok_; }
  bool Send(const std::string& s) {
    return ::send(fd_, s.data(), s.size(), MSG_NOSIGNAL) == static_cast<ssize_t>(s.size());
  }
  // What arrives before `timeout`, up to the peer's close or `enough` bytes.
  std::string Read(std::chrono::milliseconds timeout, size_t enough = 1 << 20) {
    std::string out;
    const Clock::time_point end = Clock::now() + timeout;
    while (out.size() < enough) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(end - Clock::now());
      if (left.count() <= 0) break;
      pollfd p{.fd = fd_, .events = POLLIN, .revents = 0};
      if (::poll(&p, 1, static_cast<int>(left.count())) <= 0) break;
      char buf[4096];
      const ssize_t n = ::recv(fd_, buf, sizeof buf, 0);
      if (n <= 0) break;
      out.append(buf, static_cast<size_t>(n));
    }
    return out;
  }

 private:
  int fd_;
  bool ok_ = false;
};

std::string Request(const std::string& method, const std::string& path, bool token) {
  std::string r = method + " " + path + " HTTP/1.1\r\nHost: localhost\r\n";
  if (token) r += std::string("Authorization: Bearer ") + kFloodToken + "\r\n";
  return r + "\r\n";
}

int StatusOf(const std::string& response) {
  if (response.size() < 12 || response.compare(0, 9, "HTTP/1.1 ") != 0) return 0;
  return std::atoi(response.substr(9, 3).c_str());
}

class HttpGateTest : public ::testing::Test {
 protected:
  void SetUp() override {
    absl::StatusOr<std::unique_ptr<MonitorServer>> s =
        MonitorServer::Start({.listen = "127.0.0.1:0", .token = kFloodToken}, nullptr);
    ASSERT_TRUE(s.ok()) << s.status();
    server_ = *std::move(s);
    port_ = std::stoi(server_->address().substr(server_->address().rfind(':') + 1));
  }

  // One request on a fresh connection; its status and how long the whole
  // answer took (the server closes after it). 0 when none came in 3 s.
  std::pair<int, double> Timed(const std::string& request) {
    const Clock::time_point t0 = Clock::now();
    Conn c(port_);
    if (!c.ok() || !c.Send(request)) return {0, 0};
    const std::string response = c.Read(std::chrono::seconds(3));
    return {StatusOf(response), std::chrono::duration<double>(Clock::now() - t0).count()};
  }
  void ExpectPromptAnswers(const char* under) {
    const auto [health, health_s] = Timed(Request("GET", "/healthz", false));
    EXPECT_EQ(health, 200) << under;
    EXPECT_LT(health_s, 1.0) << "/healthz under " << under;
    const auto [page, page_s] = Timed(Request("GET", "/", true));
    EXPECT_EQ(page, 200) << under;
    EXPECT_LT(page_s, 1.0) << "/ under " << under;
  }

  std::unique_ptr<MonitorServer> server_;
  int port_ = 0;
};

TEST_F(HttpGateTest, EventStreamFloodLeavesThreadsForRequests) {
  // 16 tabs of one browser, as many as the server has threads.
  std::vector<std::unique_ptr<Conn>> streams;
  int open = 0, refused = 0;
  for (int i = 0; i < 16; ++i) {
    streams.push_back(std::make_unique<Conn>(port_));
    ASSERT_TRUE(streams.back()->ok());
    ASSERT_TRUE(streams.back()->Send(Request("GET", "/api/jobs/stream", true)));
  }
  for (auto& s : streams) {
    const std::string head = s->Read(std::chrono::milliseconds(2000), 12);
    const int status = StatusOf(head);
    if (status == 200) ++open;
    if (status == 429 || status == 503) ++refused;
  }
  EXPECT_GE(open, 1);
  EXPECT_LE(open, 8) << "streams must leave threads for requests";
  EXPECT_EQ(open + refused, 16);
  ExpectPromptAnswers("16 open event streams");
}

TEST_F(HttpGateTest, SlowlorisHoldsNoThread) {
  // 20 unauthenticated clients, each sending a header line a second.
  std::vector<std::unique_ptr<Conn>> slow;
  for (int i = 0; i < 20; ++i) {
    slow.push_back(std::make_unique<Conn>(port_));
    ASSERT_TRUE(slow.back()->ok());
    ASSERT_TRUE(slow.back()->Send("GET /healthz HTTP/1.1\r\n"));
  }
  for (int second = 0; second < 2; ++second) {
    for (auto& s : slow) s->Send("X-Slow: " + std::to_string(second) + "\r\n");
    ExpectPromptAnswers("20 slowloris connections");
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
  }
  // The head deadline (3 s from accept) ends them with 408, not a thread each.
  for (auto& s : slow) EXPECT_EQ(StatusOf(s->Read(std::chrono::seconds(3), 12)), 408);
}

TEST_F(HttpGateTest, BodyWithoutLengthIsRefusedAtOnce) {
  const auto [status, seconds] = Timed("POST /login HTTP/1.1\r\nHost: localhost\r\n\r\ntoken=x");
  EXPECT_EQ(status, 411);
  EXPECT_LT(seconds, 1.0);
  const auto [chunked, chunked_s] =
      Timed("POST /login HTTP/1.1\r\nTransfer-Encoding: chunked\r\n\r\n5\r\ntoken\r\n");
  EXPECT_EQ(chunked, 411);
  EXPECT_LT(chunked_s, 1.0);
  // A body announced but larger than any form the monitor takes.
  EXPECT_EQ(Timed("POST /login HTTP/1.1\r\nContent-Length: 99999999\r\n\r\n").first, 413);
  // A body announced and sent is served.
  EXPECT_EQ(Timed("POST /login HTTP/1.1\r\nContent-Type: application/x-www-form-urlencoded\r\n"
                  "Content-Length: 7\r\n\r\ntoken=x")
                .first,
            401);
}

TEST_F(HttpGateTest, ConnectionsPerClientAreCapped) {
  // Idle connections beyond the per-address cap are told to go at once.
  std::vector<std::unique_ptr<Conn>> idle;
  for (int i = 0; i < 40; ++i) idle.push_back(std::make_unique<Conn>(port_));
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  int told = 0;
  for (auto& c : idle) told += StatusOf(c->Read(std::chrono::milliseconds(20), 12)) == 429;
  EXPECT_EQ(told, 40 - 32);
}

TEST(HttpGateTlsTest, ServesHttps) {
  test_support::ScratchDir dir("gate_tls");
  const auto cert = dir.path() / "cert.pem", key = dir.path() / "key.pem";
  const std::string cmd =
      "openssl req -x509 -newkey rsa:2048 -nodes -days 1 -subj /CN=localhost -keyout " +
      key.string() + " -out " + cert.string() + " >/dev/null 2>&1";
  if (std::system(cmd.c_str()) != 0) GTEST_SKIP() << "no openssl to make a test certificate";
  absl::StatusOr<std::unique_ptr<MonitorServer>> s = MonitorServer::Start(
      {.listen = "127.0.0.1:0", .token = kFloodToken, .tls_cert = cert, .tls_key = key}, nullptr);
  ASSERT_TRUE(s.ok()) << s.status();
  const std::string address = (*s)->address();
  httplib::SSLClient c("127.0.0.1", std::stoi(address.substr(address.rfind(':') + 1)));
  c.enable_server_certificate_verification(false);
  httplib::Result health = c.Get("/healthz");
  ASSERT_TRUE(health) << httplib::to_string(health.error());
  EXPECT_EQ(health->status, 200);
  EXPECT_EQ(health->body, "ok\n");
  httplib::Result jobs = c.Get("/api/jobs");
  ASSERT_TRUE(jobs);
  EXPECT_EQ(jobs->status, 401);
  // A client that never starts its handshake is let go, and others served.
  Conn silent(std::stoi(address.substr(address.rfind(':') + 1)));
  EXPECT_TRUE(c.Get("/healthz"));
}

}  // namespace
}  // namespace wavebake::web
