// The monitor's token check: the bearer header compares the whole token;
// sessions come only from the right token, are unguessable ids, and the
// cookie is HttpOnly and SameSite=Strict (Secure under TLS).
#include "web/http/web_auth.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace wavebake::web {
namespace {

using ::testing::HasSubstr;

TEST(WebAuthTest, BearerHeaderAndSessions) {
  WebAuth auth("tok");
  EXPECT_TRUE(auth.Allows("Bearer tok", ""));
  for (const char* bad : {"", "Bearer", "Bearer ", "Bearer to", "Bearer tokk", "bearer tok", "tok"})
    EXPECT_FALSE(auth.Allows(bad, "")) << bad;
  EXPECT_FALSE(auth.Login("nope").has_value());
  const std::optional<std::string> s = auth.Login("tok");
  ASSERT_TRUE(s.has_value());
  EXPECT_EQ(s->size(), 64u);  // 256 random bits in hex
  EXPECT_NE(*auth.Login("tok"), *s);
  EXPECT_TRUE(auth.Allows("", "a=1; wavebake_session=" + *s + "; b=2"));
  EXPECT_FALSE(auth.Allows("", "wavebake_session=" + s->substr(1)));
  EXPECT_FALSE(auth.Allows("", "other_session=" + *s));
  // A wrong header is refused even with a good cookie: no mixing.
  EXPECT_FALSE(auth.Allows("Bearer nope", "wavebake_session=" + *s));
  const std::string cookie = WebAuth::SessionCookie(*s, true);
  EXPECT_THAT(cookie, HasSubstr("HttpOnly"));
  EXPECT_THAT(cookie, HasSubstr("SameSite=Strict"));
  EXPECT_THAT(cookie, HasSubstr("Secure"));
  EXPECT_THAT(WebAuth::SessionCookie(*s, false), ::testing::Not(HasSubstr("Secure")));
}

TEST(WebAuthTest, NoTokenLetsEveryoneIn) {
  WebAuth open("");
  EXPECT_FALSE(open.enabled());
  EXPECT_TRUE(open.Allows("", ""));
}

}  // namespace
}  // namespace wavebake::web
