#include "proto/api/http_headers.h"

#include <gtest/gtest.h>

namespace reenact::proto {
namespace {

TEST(HttpHeaders, NamesCompareIgnoringAsciiCaseOnly) {
  EXPECT_TRUE(EqualsIgnoreCase("Content-Type", "content-TYPE"));
  EXPECT_TRUE(EqualsIgnoreCase("", ""));
  EXPECT_FALSE(EqualsIgnoreCase("ETag", "ETags"));
  EXPECT_FALSE(EqualsIgnoreCase("Content-Type", "Content_Type"));
  EXPECT_FALSE(EqualsIgnoreCase("\xc3\xa9", "\xc3\x89"));  // no case folding beyond ASCII
}

TEST(HttpHeaders, FindHeaderTakesTheFirstOfTheName) {
  const HttpHeaders headers = {{"ETag", "\"a\""}, {"Location", "/v1/clips/7"}, {"etag", "\"b\""}};
  EXPECT_EQ(FindHeader(headers, "etag"), "\"a\"");
  EXPECT_EQ(FindHeader(headers, "LOCATION"), "/v1/clips/7");
  EXPECT_EQ(FindHeader(headers, "Allow"), std::nullopt);
  EXPECT_EQ(FindHeader({}, "ETag"), std::nullopt);
}

}  // namespace
}  // namespace reenact::proto
