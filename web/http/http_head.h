#pragma once
// What the monitor's gate (web/http/http_gate.h) reads of a request before any
// handler thread is spent on it: whether the bytes received so far hold the
// whole request — its head and the body its Content-Length announces — and
// whether it is one the server refuses outright. Pure, so a fuzzer drives it.
#include <cstddef>
#include <string>
#include <string_view>

namespace wavebake::web {

struct HeadLimits {
  size_t max_head = 8192;     // request line and headers, as cpp-httplib's own limit
  size_t max_body = 1 << 16;  // only small forms and queries come in
};

struct HeadCheck {
  enum Kind { kIncomplete, kReady, kRefuse };
  Kind kind = kIncomplete;
  size_t request_bytes = 0;  // kReady: head and body, a prefix of what was given
  int status = 0;            // kRefuse: the HTTP status to answer
  std::string reason{};      // kRefuse: why, for the answer's body
};

// `received`: the connection's first bytes. A request whose body length is
// not announced (POST/PUT/PATCH without Content-Length, any Transfer-Encoding)
// is refused with 411: reading it to the end of the connection would hold a
// thread for as long as the client likes.
HeadCheck CheckRequestHead(std::string_view received, const HeadLimits& limits = {});

}  // namespace wavebake::web
