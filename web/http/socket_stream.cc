#include "web/http/socket_stream.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>

#include <algorithm>
#include <cerrno>

namespace wavebake::web {
namespace {

void IpAndPort(const sockaddr_storage& a, std::string& ip, int& port) {
  char text[INET6_ADDRSTRLEN] = {};
  if (a.ss_family == AF_INET) {
    const auto& v4 = reinterpret_cast<const sockaddr_in&>(a);
    inet_ntop(AF_INET, &v4.sin_addr, text, sizeof text);
    port = ntohs(v4.sin_port);
  } else if (a.ss_family == AF_INET6) {
    const auto& v6 = reinterpret_cast<const sockaddr_in6&>(a);
    inet_ntop(AF_INET6, &v6.sin6_addr, text, sizeof text);
    port = ntohs(v6.sin6_port);
  }
  ip = text;
}

}  // namespace

SocketStream::SocketStream(int fd, SSL_CTX* ssl_ctx, StreamClock::time_point read_deadline,
                           std::chrono::milliseconds write_timeout)
    : fd_(fd), read_deadline_(read_deadline), write_timeout_(write_timeout) {
  // Non-blocking: every wait is a poll with a deadline, never a blocked call.
  fcntl(fd_, F_SETFL, fcntl(fd_, F_GETFL) | O_NONBLOCK);
  if (ssl_ctx != nullptr) {
    ssl_ = SSL_new(ssl_ctx);
    if (ssl_ != nullptr) SSL_set_fd(ssl_, fd_);
  }
}

SocketStream::~SocketStream() {
  if (ssl_ == nullptr) return;
  SSL_shutdown(ssl_);  // one try: the close_notify, never a wait for the peer's
  SSL_free(ssl_);
}

bool SocketStream::Wait(short events, StreamClock::time_point deadline) const {
  for (;;) {
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - StreamClock::now());
    if (left.count() <= 0) return false;
    pollfd p{.fd = fd_, .events = events, .revents = 0};
    const int n = ::poll(&p, 1, static_cast<int>(std::min<int64_t>(left.count(), 1'000'000)));
    if (n > 0) return true;  // ready, or an error the next call reports
    if (n < 0 && errno != EINTR) return false;
  }
}

bool SocketStream::WaitForSsl(int ret, StreamClock::time_point deadline) const {
  switch (SSL_get_error(ssl_, ret)) {
    case SSL_ERROR_WANT_READ:
      return Wait(POLLIN, deadline);
    case SSL_ERROR_WANT_WRITE:
      return Wait(POLLOUT, deadline);
    default:
      return false;
  }
}

bool SocketStream::Handshake() {
  if (ssl_ == nullptr) return true;
  for (;;) {
    const int r = SSL_accept(ssl_);
    if (r == 1) return true;
    if (!WaitForSsl(r, read_deadline_)) return false;
  }
}

bool SocketStream::is_readable() const {
  if (buffer_at_ < buffer_end_ || (ssl_ != nullptr && SSL_pending(ssl_) > 0)) return true;
  return Wait(POLLIN, read_deadline_);
}

bool SocketStream::is_writable() const {
  return Wait(POLLOUT, StreamClock::now() + write_timeout_);
}

ssize_t SocketStream::read(char* ptr, size_t size) {
  const int n = static_cast<int>(std::min<size_t>(size, 1 << 30));
  if (ssl_ != nullptr) {
    for (;;) {
      const int r = SSL_read(ssl_, ptr, n);
      if (r > 0) return r;
      if (!WaitForSsl(r, read_deadline_)) return -1;
    }
  }
  if (buffer_at_ == buffer_end_) {
    for (;;) {
      const ssize_t r = ::recv(fd_, buffer_, sizeof buffer_, 0);
      if (r == 0) return 0;
      if (r > 0) {
        buffer_at_ = 0;
        buffer_end_ = static_cast<size_t>(r);
        break;
      }
      if (errno == EINTR) continue;
      if (errno != EAGAIN && errno != EWOULDBLOCK) return -1;
      if (!Wait(POLLIN, read_deadline_)) return -1;
    }
  }
  const size_t take = std::min(static_cast<size_t>(n), buffer_end_ - buffer_at_);
  std::copy_n(buffer_ + buffer_at_, take, ptr);
  buffer_at_ += take;
  return static_cast<ssize_t>(take);
}

ssize_t SocketStream::write(const char* ptr, size_t size) {
  const int n = static_cast<int>(std::min<size_t>(size, 1 << 30));
  const StreamClock::time_point deadline = StreamClock::now() + write_timeout_;
  if (ssl_ != nullptr) {
    for (;;) {
      const int r = SSL_write(ssl_, ptr, n);
      if (r > 0) return r;
      if (!WaitForSsl(r, deadline)) return -1;
    }
  }
  for (;;) {
    const ssize_t r = ::send(fd_, ptr, n, MSG_NOSIGNAL);
    if (r >= 0) return r;
    if (errno == EINTR) continue;
    if (errno != EAGAIN && errno != EWOULDBLOCK) return -1;
    if (!Wait(POLLOUT, deadline)) return -1;
  }
}

void SocketStream::get_remote_ip_and_port(std::string& ip, int& port) const {
  sockaddr_storage a{};
  socklen_t len = sizeof a;
  if (::getpeername(fd_, reinterpret_cast<sockaddr*>(&a), &len) == 0) IpAndPort(a, ip, port);
}

void SocketStream::get_local_ip_and_port(std::string& ip, int& port) const {
  sockaddr_storage a{};
  socklen_t len = sizeof a;
  if (::getsockname(fd_, reinterpret_cast<sockaddr*>(&a), &len) == 0) IpAndPort(a, ip, port);
}

}  // namespace wavebake::web
