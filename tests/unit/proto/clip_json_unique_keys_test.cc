#include "proto/clip/json_unique_keys.h"

#include <string>

#include <gtest/gtest.h>

namespace reenact::proto {
namespace {

TEST(ClipJsonUniqueKeys, FindsARepeatedKeyAtAnyDepth) {
  EXPECT_EQ(FirstDuplicateKey(R"({"title": "a", "n": 1, "title": "b"})"), "title");
  EXPECT_EQ(FirstDuplicateKey(R"({"location": {"lat_deg": 1, "lon_deg": 2, "lat_deg": 3}})"),
            "location.lat_deg");
  EXPECT_EQ(FirstDuplicateKey(R"({"parts": {"frames": [{"bytes": 1, "sha256": "x"},)"
                              R"( {"bytes": 2}, [3, {"x": 0}], {"sha256": "y", "sha256": "z"}]}})"),
            "parts.frames[3].sha256");
  EXPECT_EQ(FirstDuplicateKey(R"([1, [2, {"a": {"b": null, "b": [true]}}]])"), "[1][1].a.b");
  // The first repeat in document order, whatever its depth.
  EXPECT_EQ(FirstDuplicateKey(R"({"a": {"x": 1, "x": 2}, "a": 3})"), "a.x");
}

TEST(ClipJsonUniqueKeys, EqualKeysInDifferentObjectsAreFine) {
  EXPECT_EQ(FirstDuplicateKey(R"({"a": {"k": 1}, "b": {"k": 2}, "k": {"k": {"k": 3}}})"),
            std::nullopt);
  EXPECT_EQ(FirstDuplicateKey(R"({"frames": [{"bytes": 1}, {"bytes": 2}, {"bytes": 3}]})"),
            std::nullopt);
  EXPECT_EQ(FirstDuplicateKey(R"({"a": 1, "A": 2, "a ": 3})"), std::nullopt);
  EXPECT_EQ(FirstDuplicateKey("[]"), std::nullopt);
  EXPECT_EQ(FirstDuplicateKey("42"), std::nullopt);
}

TEST(ClipJsonUniqueKeys, KeysCompareAfterUnescaping) {
  // "\u0061" is "a": the same key written two ways.
  EXPECT_EQ(FirstDuplicateKey(R"({"a": 1, "\u0061": 2})"), "a");
}

TEST(ClipJsonUniqueKeys, MalformedTextIsLeftToTheParser) {
  EXPECT_EQ(FirstDuplicateKey(R"({"a": 1, "b": )"), std::nullopt);
  EXPECT_EQ(FirstDuplicateKey(""), std::nullopt);
  // A repeat before the text goes wrong is still found.
  EXPECT_EQ(FirstDuplicateKey(R"({"a": 1, "a": 2, )"), "a");
}

}  // namespace
}  // namespace reenact::proto
