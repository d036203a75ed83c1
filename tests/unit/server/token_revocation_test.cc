// Token revocation through the store and the DELETE /v1/me/token route, without sockets, on both
// storage engines.
#include <gtest/gtest.h>

#include "tests/unit/server/server_test_util.h"

namespace reenact::server {
namespace {

using testing::MakeTestClip;
class TokenRevocationTest : public testing::EngineServiceFixture {};
INSTANTIATE_TEST_SUITE_P(Engines, TokenRevocationTest,
                         ::testing::Values(testing::Engine::kSqlite, testing::Engine::kPostgres),
                         testing::EngineName);

TEST_P(TokenRevocationTest, RevokedTokenNoLongerWritesAndOthersStillDo) {
  const std::string id = Create(MakeTestClip(1, 2), alice_);
  auto second = AddTokenForUser(*storage_.metadata, "alice");
  ASSERT_TRUE(second.ok()) << second.error().message;
  EXPECT_NE(*second, alice_);

  Response revoke = Call("DELETE", "/v1/me/token", alice_);
  EXPECT_EQ(revoke.status, 204) << revoke.body;

  const int64_t drafts_before = *storage_.metadata->CountClips(ClipState::kDraft);
  Response denied =
      Call("POST", "/v1/clips", alice_, MakeTestClip(3, 4).manifest_json, "application/json");
  EXPECT_EQ(denied.status, 401);
  EXPECT_EQ(ErrorCode(denied), "unauthorized");
  EXPECT_NE(ErrorMessage(denied).find("revoked"), std::string::npos);
  EXPECT_EQ(*storage_.metadata->CountClips(ClipState::kDraft), drafts_before)
      << "a refused request stored something";

  // The other token of the same user still works, on the same clip.
  EXPECT_EQ(Call("POST", "/v1/clips/" + id + "/publish", *second).status, 409);
}

TEST_P(TokenRevocationTest, RevokeAllTokensOfAUser) {
  auto second = AddTokenForUser(*storage_.metadata, "bob");
  ASSERT_TRUE(second.ok());
  auto revoked = storage_.metadata->RevokeUserTokens("bob");
  ASSERT_TRUE(revoked.ok());
  EXPECT_EQ(*revoked, 2);
  EXPECT_EQ(Call("GET", "/v1/me/clips", bob_).status, 401);
  EXPECT_EQ(Call("GET", "/v1/me/clips", *second).status, 401);
  EXPECT_EQ(Call("GET", "/v1/me/clips", alice_).status, 200);
}

TEST_P(TokenRevocationTest, UnknownUserIsAClearError) {
  auto revoked = storage_.metadata->RevokeUserTokens("nobody");
  ASSERT_FALSE(revoked.ok());
  EXPECT_EQ(revoked.error().code, "not_found");
  auto added = AddTokenForUser(*storage_.metadata, "nobody");
  ASSERT_FALSE(added.ok());
  EXPECT_EQ(added.error().code, "not_found");
}

TEST_P(TokenRevocationTest, RevokeRouteNeedsAToken) {
  Response r = Call("DELETE", "/v1/me/token");
  EXPECT_EQ(r.status, 401);
  EXPECT_EQ(ErrorCode(r), "unauthorized");
  EXPECT_EQ(Call("GET", "/v1/me/token", alice_).status, 405);
}

}  // namespace
}  // namespace reenact::server
