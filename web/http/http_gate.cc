#include "web/http/http_gate.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/eventfd.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>

#include "absl/strings/str_cat.h"

namespace wavebake::web {
namespace {

// cpp-httplib listens with a backlog of 5: a burst of connections would
// overflow it and wait for SYN retransmits (a second each) before this
// gate even sees them.
constexpr int kBacklog = 512;
// A connection polled and found without new bytes (a kernel that does not
// honour SO_RCVLOWAT for it) is left alone this long.
constexpr auto kQuiet = std::chrono::milliseconds(20);

std::string ClientAddress(const sockaddr_storage& a) {
  char text[INET6_ADDRSTRLEN] = {};
  if (a.ss_family == AF_INET)
    inet_ntop(AF_INET, &reinterpret_cast<const sockaddr_in&>(a).sin_addr, text, sizeof text);
  else if (a.ss_family == AF_INET6)
    inet_ntop(AF_INET6, &reinterpret_cast<const sockaddr_in6&>(a).sin6_addr, text, sizeof text);
  return text;
}

const char* StatusText(int status) {
  switch (status) {
    case 400:
      return "Bad Request";
    case 408:
      return "Request Timeout";
    case 411:
      return "Length Required";
    case 413:
      return "Payload Too Large";
    case 429:
      return "Too Many Requests";
    case 431:
      return "Request Header Fields Too Large";
    default:
      return "Service Unavailable";
  }
}

}  // namespace

HttpGate::HttpGate(int listen_fd, GateOptions options, Serve serve)
    : options_(options),
      listen_fd_(listen_fd),
      wake_fd_(::eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK)),
      peek_(options.limits.max_head + options.limits.max_body + 1),
      pool_(options.threads, options.max_queued,
            [serve = std::move(serve)](BoundedPool::Connection c) { serve(c.fd, c.deadline); }) {
  ::listen(listen_fd_, kBacklog);  // again: only the backlog changes
  ::fcntl(listen_fd_, F_SETFL, ::fcntl(listen_fd_, F_GETFL) | O_NONBLOCK);
  thread_ = std::thread([this] { Run(); });
}

HttpGate::~HttpGate() { Stop(); }

void HttpGate::Stop() {
  if (thread_.joinable()) {
    const uint64_t one = 1;
    [[maybe_unused]] ssize_t w = ::write(wake_fd_, &one, sizeof one);
    thread_.join();
    for (const Waiting& w : waiting_) ::close(w.fd);
    waiting_.clear();
    ::close(listen_fd_);
    ::close(wake_fd_);
  }
  pool_.Stop();
}

void HttpGate::Run() {
  std::vector<pollfd> fds;
  std::vector<size_t> polled;  // fds[2 + i] is waiting_[polled[i]]
  for (;;) {
    const Clock::time_point now = Clock::now();
    fds.assign({{.fd = wake_fd_, .events = POLLIN, .revents = 0},
                {.fd = listen_fd_, .events = POLLIN, .revents = 0}});
    polled.clear();
    Clock::time_point next = now + std::chrono::seconds(1);
    for (size_t i = 0; i < waiting_.size(); ++i) {
      next = std::min(next, waiting_[i].deadline);
      if (waiting_[i].quiet_until > now) {
        next = std::min(next, waiting_[i].quiet_until);
        continue;
      }
      fds.push_back({.fd = waiting_[i].fd, .events = POLLIN | POLLRDHUP, .revents = 0});
      polled.push_back(i);
    }
    const auto wait = std::chrono::ceil<std::chrono::milliseconds>(next - now);
    if (::poll(fds.data(), fds.size(), static_cast<int>(std::max<int64_t>(wait.count(), 0))) < 0 &&
        errno != EINTR)
      continue;
    if (fds[0].revents != 0) return;  // Stop()

    std::vector<bool> gone(waiting_.size(), false);
    for (size_t k = 0; k < polled.size(); ++k) {
      const short ev = fds[2 + k].revents;
      if (ev == 0) continue;
      gone[polled[k]] = Examine(waiting_[polled[k]], (ev & (POLLHUP | POLLRDHUP | POLLERR)) != 0);
    }
    const Clock::time_point after = Clock::now();
    for (size_t i = 0; i < waiting_.size(); ++i) {
      if (gone[i] || waiting_[i].deadline > after) continue;
      Answer(waiting_[i].fd, 408, "the request did not arrive in time");
      gone[i] = true;
    }
    size_t kept = 0;
    for (size_t i = 0; i < waiting_.size(); ++i) {
      if (gone[i]) {
        Forget(waiting_[i]);
        continue;
      }
      waiting_[kept++] = std::move(waiting_[i]);
    }
    waiting_.resize(kept);
    if (fds[1].revents != 0) Accept();
  }
}

void HttpGate::Accept() {
  for (;;) {
    sockaddr_storage peer{};
    socklen_t len = sizeof peer;
    const int fd = ::accept4(listen_fd_, reinterpret_cast<sockaddr*>(&peer), &len, SOCK_CLOEXEC);
    if (fd < 0) return;  // EAGAIN: all taken; anything else: next poll
    const int on = 1;
    ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &on, sizeof on);  // a frame: no Nagle wait
    std::string client = ClientAddress(peer);
    if (waiting_.size() >= options_.max_waiting) {
      Answer(fd, 503, "too many connections");
      continue;
    }
    size_t& mine = per_client_[client];
    if (mine >= options_.max_waiting_per_client) {
      Answer(fd, 429, "too many connections from this address");
      continue;
    }
    ++mine;
    waiting_.push_back(
        {.fd = fd, .client = std::move(client), .deadline = Clock::now() + options_.head_deadline});
  }
}

bool HttpGate::Examine(Waiting& w, bool hung_up) {
  const ssize_t n = ::recv(w.fd, peek_.data(), peek_.size(), MSG_PEEK | MSG_DONTWAIT);
  if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR)) return false;
  if (n <= 0) {  // gone before its request
    ::close(w.fd);
    return true;
  }
  HeadCheck check;
  if (options_.tls) {
    check.kind = HeadCheck::kReady;  // the handshake has begun: the thread reads the rest
  } else {
    check =
        CheckRequestHead(std::string_view(peek_.data(), static_cast<size_t>(n)), options_.limits);
  }
  if (check.kind == HeadCheck::kRefuse) {
    Answer(w.fd, check.status, check.reason);
    return true;
  }
  if (check.kind == HeadCheck::kReady) {
    const int one = 1;
    ::setsockopt(w.fd, SOL_SOCKET, SO_RCVLOWAT, &one, sizeof one);
    if (!pool_.Offer({.fd = w.fd, .deadline = Clock::now() + options_.head_deadline}))
      Answer(w.fd, 503, "the server is busy");
    return true;
  }
  if (static_cast<size_t>(n) == w.received) {
    if (hung_up) {  // half a request and the client stopped sending
      ::close(w.fd);
      return true;
    }
    w.quiet_until = Clock::now() + kQuiet;
    return false;
  }
  // Woken again only once more bytes came than were looked at.
  w.received = static_cast<size_t>(n);
  const int more = static_cast<int>(std::min<size_t>(w.received + 1, 1 << 30));
  ::setsockopt(w.fd, SOL_SOCKET, SO_RCVLOWAT, &more, sizeof more);
  return false;
}

void HttpGate::Answer(int fd, int status, const std::string& reason) {
  if (!options_.tls) {
    // Read what came, so that closing sends the answer and not a reset.
    for (int i = 0; i < 8 && ::recv(fd, peek_.data(), peek_.size(), MSG_DONTWAIT) > 0; ++i) {
    }
    const std::string body = reason + "\n";
    const std::string reply = absl::StrCat(
        "HTTP/1.1 ", status, " ", StatusText(status),
        "\r\nContent-Type: text/plain\r\nConnection: close\r\nRetry-After: 1\r\nContent-Length: ",
        body.size(), "\r\n\r\n", body);
    [[maybe_unused]] ssize_t sent =
        ::send(fd, reply.data(), reply.size(), MSG_DONTWAIT | MSG_NOSIGNAL);
    ::shutdown(fd, SHUT_WR);
  }
  ::close(fd);
}

void HttpGate::Forget(const Waiting& w) {
  auto it = per_client_.find(w.client);
  if (it != per_client_.end() && --it->second == 0) per_client_.erase(it);
}

}  // namespace wavebake::web
