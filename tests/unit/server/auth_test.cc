#include "server/auth/token.h"

#include <fstream>
#include <iterator>
#include <set>

#include <gtest/gtest.h>

#include "tests/unit/server/server_test_util.h"

namespace reenact::server {
namespace {

TEST(Token, HasAtLeast128RandomBitsAndDiffers) {
  std::set<std::string> tokens;
  for (int i = 0; i < 50; ++i) {
    auto token = GenerateToken();
    ASSERT_TRUE(token.ok());
    EXPECT_EQ(token->rfind("rnk_", 0), 0u);
    EXPECT_GE(token->size() - 4, 32u);  // hex digits: 4 bits each, >= 128 bits
    tokens.insert(*token);
  }
  EXPECT_EQ(tokens.size(), 50u);
}

TEST(Token, HashIsSha256OfTheText) {
  // SHA-256("abc") from FIPS 180-2, appendix B.1.
  EXPECT_EQ(HashToken("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
}

TEST(Token, ConstantTimeEquals) {
  EXPECT_TRUE(ConstantTimeEquals("abc", "abc"));
  EXPECT_FALSE(ConstantTimeEquals("abc", "abd"));
  EXPECT_FALSE(ConstantTimeEquals("abc", "abcd"));
}

TEST(Token, ParseBearer) {
  EXPECT_EQ(ParseBearer("Bearer rnk_x"), "rnk_x");
  EXPECT_EQ(ParseBearer("bearer   rnk_x "), "rnk_x");
  EXPECT_FALSE(ParseBearer("Basic abc").has_value());
  EXPECT_FALSE(ParseBearer("Bearer ").has_value());
  EXPECT_FALSE(ParseBearer("Bearer a b").has_value());
}

TEST(Token, StoredOnlyAsHashAndAuthenticates) {
  testing::TempDir dir;
  const std::string path = (dir.path() / "db.sqlite").string();
  std::string token;
  {
    auto storage = OpenSqliteStorage(path);
    ASSERT_TRUE(storage.ok());
    auto added = AddUserWithToken(*storage->metadata, "carol");
    ASSERT_TRUE(added.ok());
    token = *added;
    auto user = Authenticate(*storage->metadata, token);
    ASSERT_TRUE(user.ok() && user->has_value());
    EXPECT_EQ((*user)->name, "carol");
    auto wrong = Authenticate(*storage->metadata, token + "x");
    ASSERT_TRUE(wrong.ok());
    EXPECT_FALSE(wrong->has_value());
    EXPECT_EQ(AddUserWithToken(*storage->metadata, "carol").error().code, "conflict");
    EXPECT_EQ(AddUserWithToken(*storage->metadata, "").error().code, "invalid_argument");
  }
  // No database file holds the token's text (the WAL is checkpointed on close).
  for (const auto& entry : std::filesystem::directory_iterator(dir.path())) {
    std::ifstream in(entry.path(), std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), {});
    EXPECT_EQ(bytes.find(token.substr(4)), std::string::npos) << entry.path();
    if (entry.path().filename() == "db.sqlite") {
      EXPECT_NE(bytes.find(HashToken(token)), std::string::npos);
    }
  }
}

}  // namespace
}  // namespace reenact::server
