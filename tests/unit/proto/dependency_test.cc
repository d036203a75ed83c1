// proto/ holds the formats of clients and server alike. OpenCV codes the frame images inside
// proto/clip/frame_codec.cc only: no proto/ header includes it, so no OpenCV type reaches the
// server through proto/ (reenact_proto links OpenCV privately). proto/ includes no client,
// server, vision or synthetic-scene code.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/support/include_scan.h"

namespace reenact::test_support {
namespace {

using testing::IsEmpty;

TEST(ProtoDependencies, NoHeaderIncludesOpenCv) {
  EXPECT_THAT(BreakingUnder("proto",
                            [](const IncludeLine& i) {
                              return i.file.ends_with(".h") && IsOpenCvHeader(i.header);
                            }),
              IsEmpty());
}

TEST(ProtoDependencies, IncludesNoClientServerVisionOrSyntheticCode) {
  EXPECT_THAT(BreakingUnder("proto",
                            [](const IncludeLine& i) {
                              return StartsWithAnyOf(
                                  i.header, {"capture-client/", "viewer-client/", "server/",
                                             "vision/", "synthetic/"});
                            }),
              IsEmpty());
}

}  // namespace
}  // namespace reenact::test_support
