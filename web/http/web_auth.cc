#include "web/http/web_auth.h"

#include <openssl/rand.h>

#include <algorithm>

#include "absl/strings/escaping.h"
#include "absl/strings/str_cat.h"

namespace wavebake::web {
namespace {

std::string_view Trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

// The value of cookie `name` in a Cookie header ("a=1; name=value; b=2").
std::string_view CookieValue(std::string_view header, std::string_view name) {
  while (!header.empty()) {
    const size_t end = std::min(header.find(';'), header.size());
    std::string_view part = Trim(header.substr(0, end));
    header.remove_prefix(std::min(end + 1, header.size()));
    if (part.size() > name.size() && part.starts_with(name) && part[name.size()] == '=') {
      return part.substr(name.size() + 1);
    }
  }
  return {};
}

}  // namespace

bool WebAuth::Allows(std::string_view authorization, std::string_view cookie) const {
  if (!enabled()) return true;
  constexpr std::string_view kBearer = "Bearer ";
  if (authorization.starts_with(kBearer))
    return token_.Matches(authorization.substr(kBearer.size()));
  const std::string_view session = CookieValue(cookie, kSessionCookie);
  if (session.empty()) return false;
  std::lock_guard lock(mu_);
  auto it = sessions_.find(std::string(session));
  if (it == sessions_.end()) return false;
  if (Clock::now() < it->second) return true;
  sessions_.erase(it);
  return false;
}

std::optional<std::string> WebAuth::Login(std::string_view token) {
  if (enabled() && !token_.Matches(token)) return std::nullopt;
  unsigned char bytes[32];
  if (RAND_bytes(bytes, sizeof bytes) != 1) return std::nullopt;
  std::string id =
      absl::BytesToHexString(absl::string_view(reinterpret_cast<const char*>(bytes), sizeof bytes));
  std::lock_guard lock(mu_);
  const Clock::time_point now = Clock::now();
  std::erase_if(sessions_, [&](const auto& s) { return s.second <= now; });
  if (sessions_.size() >= kMaxSessions) {  // the one closest to expiry goes
    sessions_.erase(std::min_element(sessions_.begin(), sessions_.end(),
                                     [](auto& a, auto& b) { return a.second < b.second; }));
  }
  sessions_[id] = now + kSessionLife;
  return id;
}

std::string WebAuth::SessionCookie(const std::string& session, bool secure) {
  return absl::StrCat(kSessionCookie, "=", session, "; Path=/; HttpOnly; SameSite=Strict; Max-Age=",
                      std::chrono::seconds(kSessionLife).count(), secure ? "; Secure" : "");
}

}  // namespace wavebake::web
