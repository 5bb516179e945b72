#pragma once
// One accepted connection as cpp-httplib's Stream, plain or TLS, for the
// monitor's own serving loop (web/http/http_gate.h): reads end at one deadline
// for the whole request (TLS handshake included), not a timeout per read, so
// a client trickling bytes cannot hold the thread longer; each write waits
// at most `write_timeout` for the client to take bytes.
#include <httplib.h>
#include <openssl/ssl.h>

#include <chrono>
#include <memory>
#include <string>

namespace wavebake::web {

using StreamClock = std::chrono::steady_clock;

class SocketStream : public httplib::Stream {
 public:
  // Borrows `fd` (the caller closes it). `ssl_ctx` null: plain HTTP.
  SocketStream(int fd, SSL_CTX* ssl_ctx, StreamClock::time_point read_deadline,
               std::chrono::milliseconds write_timeout);
  ~SocketStream() override;

  // TLS: completes the handshake before the read deadline; plain: true.
  bool Handshake();

  bool is_readable() const override;
  bool is_writable() const override;
  ssize_t read(char* ptr, size_t size) override;
  ssize_t write(const char* ptr, size_t size) override;
  void get_remote_ip_and_port(std::string& ip, int& port) const override;
  void get_local_ip_and_port(std::string& ip, int& port) const override;
  int socket() const override { return fd_; }

 private:
  // Waits for `events` on the socket until `deadline`; false at the deadline.
  bool Wait(short events, StreamClock::time_point deadline) const;
  // After an OpenSSL call returned `ret`: waits as it asks; false to give up.
  bool WaitForSsl(int ret, StreamClock::time_point deadline) const;

  int fd_;
  SSL* ssl_ = nullptr;
  // cpp-httplib reads a request's head a byte at a time: served from here,
  // not a recv each (OpenSSL buffers a whole record itself).
  char buffer_[4096];
  size_t buffer_at_ = 0, buffer_end_ = 0;
  StreamClock::time_point read_deadline_;
  std::chrono::milliseconds write_timeout_;
};

}  // namespace wavebake::web
