#include "web/http/http_head.h"

#include <charconv>

#include "absl/strings/ascii.h"
#include "absl/strings/match.h"

namespace wavebake::web {
namespace {

// Debian's abseil has a string_view of its own.
absl::string_view A(std::string_view s) { return {s.data(), s.size()}; }

HeadCheck Refuse(int status, std::string reason) {
  return {.kind = HeadCheck::kRefuse, .status = status, .reason = std::move(reason)};
}

}  // namespace

// Lines as cpp-httplib reads them: up to each '\n'; a header line counts
// only when it ends in CRLF (others it skips), and the head ends at the first
// line that is CRLF alone. Reading it any other way would let through a
// request whose body cpp-httplib then waits for.
HeadCheck CheckRequestHead(std::string_view received, const HeadLimits& limits) {
  const std::string_view seen = received.substr(0, limits.max_head);
  size_t line_end = seen.find('\n');
  if (line_end == std::string_view::npos) {
    if (received.size() >= limits.max_head) return Refuse(431, "request head too large");
    return {};
  }
  const std::string_view request_line = seen.substr(0, line_end);
  const size_t space = request_line.find(' ');
  if (space == 0 || space == std::string_view::npos) return Refuse(400, "malformed request line");
  const std::string_view method = request_line.substr(0, space);
  const bool body_method = method == "POST" || method == "PUT" || method == "PATCH";

  bool has_length = false;
  size_t body = 0;
  size_t head_bytes = 0;
  for (size_t at = line_end + 1;; at = line_end + 1) {
    line_end = seen.find('\n', at);
    if (line_end == std::string_view::npos) {
      if (received.size() >= limits.max_head) return Refuse(431, "request head too large");
      return {};
    }
    const std::string_view line = seen.substr(at, line_end - at);  // without its '\n'
    if (line == "\r") {
      head_bytes = line_end + 1;
      break;
    }
    if (!line.ends_with('\r')) continue;
    const size_t colon = line.find(':');
    if (colon == std::string_view::npos) continue;
    const std::string_view name = line.substr(0, colon);
    const absl::string_view value = absl::StripAsciiWhitespace(A(line.substr(colon + 1)));
    if (absl::EqualsIgnoreCase(A(name), "Transfer-Encoding"))
      return Refuse(411, "a body needs a Content-Length (no Transfer-Encoding)");
    if (!absl::EqualsIgnoreCase(A(name), "Content-Length")) continue;
    size_t n = 0;
    const auto [ptr, ec] = std::from_chars(value.data(), value.data() + value.size(), n);
    if (value.empty() || ec != std::errc{} || ptr != value.data() + value.size())
      return Refuse(400, "Content-Length is not a number");
    if (has_length && n != body) return Refuse(400, "two different Content-Lengths");
    has_length = true;
    body = n;
  }
  if (body_method && !has_length) return Refuse(411, "a body needs a Content-Length");
  if (body > limits.max_body) return Refuse(413, "request body too large");
  if (received.size() - head_bytes < body) return {};
  return {.kind = HeadCheck::kReady, .request_bytes = head_bytes + body};
}

}  // namespace wavebake::web
