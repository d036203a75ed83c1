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

TEST(ClipContentHash, HasherMatchesPublishedVectors) {
  Sha256Hasher empty;
  EXPECT_EQ(empty.FinalHex(), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  Sha256Hasher abc;
  abc.Update(std::string_view("a"));
  abc.Update(std::string_view(""));
  abc.Update(std::string_view("bc"));
  EXPECT_EQ(abc.FinalHex(), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  // FIPS 180-2 test vector 3: one million 'a', given in pieces of 1000.
  Sha256Hasher million;
  const std::string thousand(1000, 'a');
  for (int i = 0; i < 1000; ++i) million.Update(thousand);
  EXPECT_EQ(million.FinalHex(), "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

TEST(ClipContentHash, HasherInPiecesEqualsOneShot) {
  std::string bytes(3 * 1024 * 1024 + 17, '\0');
  for (size_t i = 0; i < bytes.size(); ++i)
    bytes[i] = static_cast<char>((i * 131 + i / 977) & 0xFF);
  const std::string expected = Sha256Hex(bytes);
  for (size_t piece : {size_t{1} << 20, size_t{63}, size_t{64}, size_t{65}, bytes.size()}) {
    Sha256Hasher hasher;
    for (size_t at = 0; at < bytes.size(); at += piece) {
      hasher.Update(std::string_view(bytes).substr(at, piece));
    }
    EXPECT_EQ(hasher.FinalHex(), expected) << "pieces of " << piece;
  }
}

TEST(ClipContentHash, HasherStartsOverAfterFinalAndMoves) {
  Sha256Hasher hasher;
  hasher.Update(std::string_view("something else"));
  EXPECT_EQ(hasher.FinalHex(), Sha256Hex(std::string_view("something else")));
  const std::vector<uint8_t> abc = {'a', 'b', 'c'};
  hasher.Update(abc);
  Sha256Hasher moved = std::move(hasher);
  EXPECT_EQ(moved.FinalHex(), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
}

TEST(ClipContentHash, RecognisesHexForm) {
  EXPECT_TRUE(IsSha256Hex(Sha256Hex(std::string_view("x"))));
  EXPECT_FALSE(IsSha256Hex("E3B0C44298FC1C149AFBF4C8996FB92427AE41E4649B934CA495991B7852B855"));
  EXPECT_FALSE(IsSha256Hex("e3b0"));
  EXPECT_FALSE(IsSha256Hex(std::string(64, 'g')));
}

}  // namespace
}  // namespace reenact::proto
