#include "proto/clip/content_hash.h"

#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace reenact::proto {
namespace {

// FIPS 180-2 / NIST test vectors.
TEST(ClipContentHash, MatchesPublishedVectors) {
  EXPECT_EQ(Sha256Hex(std::string_view("")),
            "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(Sha256Hex(std::string_view("abc")),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(Sha256Hex(std::string_view("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq")),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
}

TEST(ClipContentHash, SpanAndStringAgree) {
  const std::vector<uint8_t> bytes = {'a', 'b', 'c'};
  EXPECT_EQ(Sha256Hex(bytes), Sha256Hex(std::string_view("abc")));
}

TEST(ClipContentHash, RecognisesHexForm) {
  EXPECT_TRUE(IsSha256Hex(Sha256Hex(std::string_view("x"))));
  EXPECT_FALSE(IsSha256Hex("E3B0C44298FC1C149AFBF4C8996FB92427AE41E4649B934CA495991B7852B855"));
  EXPECT_FALSE(IsSha256Hex("e3b0"));
  EXPECT_FALSE(IsSha256Hex(std::string(64, 'g')));
}

}  // namespace
}  // namespace reenact::proto
