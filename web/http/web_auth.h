#pragma once
// The monitor's bearer token (DESIGN.md §4: HTTP behind the same token as
// gRPC). A request is let in by `Authorization: Bearer <token>` (scrapers,
// scripts) or by the session cookie a browser gets from POST /login with the
// token in a form (pages cannot set headers on navigation, and a token in a
// URL ends up in logs and history). Sessions are random 256-bit ids held in
// memory, HttpOnly and SameSite=Strict, for at most 12 hours.
#include <chrono>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>

#include "coordinator/service/auth.h"

namespace wavebake::web {

inline constexpr char kSessionCookie[] = "wavebake_session";

class WebAuth {
 public:
  explicit WebAuth(std::string token) : token_(std::move(token)) {}
  bool enabled() const { return token_.enabled(); }

  // authorization: the header's value ("" when absent); cookie: the Cookie header.
  bool Allows(std::string_view authorization, std::string_view cookie) const;
  // A new session for the right token; nullopt for a wrong one.
  std::optional<std::string> Login(std::string_view token);
  // The Set-Cookie value of a session (Secure when served over TLS).
  static std::string SessionCookie(const std::string& session, bool secure);

 private:
  using Clock = std::chrono::steady_clock;
  static constexpr std::chrono::hours kSessionLife{12};
  static constexpr size_t kMaxSessions = 1024;

  const TokenAuth token_;  // the gRPC services' check (coordinator/service/auth.h)
  mutable std::mutex mu_;
  mutable std::map<std::string, Clock::time_point> sessions_;  // id -> expiry
};

}  // namespace wavebake::web
