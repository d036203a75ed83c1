// vision/ builds on common/, Eigen, OpenCV and the standard library only (DESIGN.md): no file
// formats, no client code, so that both clients can link it.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/support/include_scan.h"

namespace reenact::test_support {
namespace {

using testing::IsEmpty;

TEST(VisionDependencies, IncludesOnlyCommonVisionEigenOpenCvAndStd) {
  EXPECT_THAT(
      BreakingUnder("vision",
                    [](const IncludeLine& i) {
                      return !(StartsWithAnyOf(i.header, {"common/", "vision/", "Eigen/"}) ||
                               IsOpenCvHeader(i.header) || IsStdHeader(i.header));
                    }),
      IsEmpty());
}

}  // namespace
}  // namespace reenact::test_support
