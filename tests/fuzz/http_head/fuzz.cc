// What a client sends the web monitor, as its gate reads it before a thread
// is spent (web/http/http_head.h), then as cpp-httplib parses what the gate let
// through (on an in-memory stream, no socket). Properties beyond "no
// crash": a ready request is a prefix of the bytes within the limits and
// is ready again on exactly those bytes and not one fewer; a refusal is one
// of the statuses the gate answers; and cpp-httplib, given a ready request,
// answers it from those bytes alone (its reads never run past them).
#include <httplib.h>

#include "tests/fuzz/fuzz_util.h"
#include "web/http/http_head.h"

namespace wavebake::fuzz {

std::vector<std::string> Seeds() {
  return {"GET /healthz HTTP/1.1\r\nHost: a\r\n\r\n",
          "POST /login HTTP/1.1\r\nContent-Type: application/x-www-form-urlencoded\r\n"
          "Content-Length: 7\r\n\r\ntoken=x",
          "POST /login HTTP/1.1\r\nTransfer-Encoding: chunked\r\n\r\n5\r\ntoken\r\n0\r\n\r\n",
          "GET /api/jobs/stream HTTP/1.1\r\nAuthorization: Bearer t\r\nContent-Length: 0\r\n"
          "Content-Length: 0\r\n\r\n",
          "GET /api/jobs/1/relight?probe=builtin:sky&rot=0.5 HTTP/1.0\r\nRange: bytes=0-1\r\n\r\n"};
}

// The bytes the gate let through, then end of stream; writes are counted.
class MemoryStream final : public httplib::Stream {
 public:
  explicit MemoryStream(std::string_view in) : in_(in) {}
  bool is_readable() const override { return true; }
  bool is_writable() const override { return true; }
  ssize_t read(char* ptr, size_t size) override {
    const size_t n = std::min(size, in_.size());
    std::copy_n(in_.data(), n, ptr);
    in_.remove_prefix(n);
    return static_cast<ssize_t>(n);
  }
  ssize_t write(const char*, size_t size) override {
    written += size;
    return static_cast<ssize_t>(size);
  }
  void get_remote_ip_and_port(std::string& ip, int& port) const override {
    ip = "127.0.0.1";
    port = 1;
  }
  void get_local_ip_and_port(std::string& ip, int& port) const override {
    ip = "127.0.0.1";
    port = 2;
  }
  int socket() const override { return -1; }
  size_t written = 0;

 private:
  std::string_view in_;
};

class OneRequestServer final : public httplib::Server {
 public:
  OneRequestServer() {
    set_payload_max_length(web::HeadLimits{}.max_body);
    Get(".*", [](const httplib::Request&, httplib::Response& res) {
      res.set_content("g", "text/plain");
    });
    Post(".*", [](const httplib::Request& req, httplib::Response& res) {
      res.set_content(req.body, "text/plain");
    });
  }
  size_t Serve(std::string_view request) {
    MemoryStream s(request);
    bool closed = false;
    process_request(s, true, closed, nullptr);
    return s.written;
  }
};

}  // namespace wavebake::fuzz

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace wavebake::web;
  using wavebake::fuzz::Require;
  const std::string_view in(reinterpret_cast<const char*>(data), size);
  const HeadLimits limits;
  const HeadCheck c = CheckRequestHead(in, limits);
  if (c.kind == HeadCheck::kRefuse) {
    Require(c.status == 400 || c.status == 411 || c.status == 413 || c.status == 431,
            "a status the gate answers");
    Require(!c.reason.empty(), "a refusal says why");
    return 0;
  }
  if (c.kind == HeadCheck::kIncomplete) {
    Require(in.size() < limits.max_head + limits.max_body, "incomplete only within the limits");
    return 0;
  }
  Require(c.request_bytes >= 4 && c.request_bytes <= in.size(), "ready on bytes given");
  Require(c.request_bytes <= limits.max_head + limits.max_body, "within the limits");
  const std::string_view request = in.substr(0, c.request_bytes);
  const HeadCheck again = CheckRequestHead(request, limits);
  Require(again.kind == HeadCheck::kReady && again.request_bytes == c.request_bytes,
          "ready on exactly its own bytes");
  Require(CheckRequestHead(request.substr(0, request.size() - 1), limits).kind ==
              HeadCheck::kIncomplete,
          "not ready one byte short");
  static wavebake::fuzz::OneRequestServer server;
  Require(server.Serve(request) > 0, "cpp-httplib answers what the gate let through");
  return 0;
}
