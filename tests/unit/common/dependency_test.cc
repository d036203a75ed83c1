// common/ is Eigen + the standard library only (DESIGN.md): fail if another library leaks in.
// The compiler's own SIMD intrinsics headers (x86 SSE2, Arm NEON) are part of the toolchain,
// not a library, and are allowed.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/support/include_scan.h"

namespace reenact::test_support {
namespace {

using testing::IsEmpty;

TEST(CommonDependencies, IncludesOnlyEigenStdAndCommon) {
  EXPECT_THAT(BreakingUnder("common",
                            [](const IncludeLine& i) {
                              const bool intrinsics =
                                  i.header == "emmintrin.h" || i.header == "arm_neon.h";
                              return !(StartsWithAnyOf(i.header, {"common/", "Eigen/"}) ||
                                       intrinsics || IsStdHeader(i.header));
                            }),
              IsEmpty());
}

}  // namespace
}  // namespace reenact::test_support
