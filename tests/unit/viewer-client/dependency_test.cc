// The viewer includes nothing of the capture client or the server (DESIGN.md): what both
// clients need lives in the libraries they share (common/, proto/, vision/, synthetic/).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/support/include_scan.h"

namespace reenact::test_support {
namespace {

using testing::IsEmpty;

TEST(ViewerDependencies, IncludesNothingOfTheCaptureClientOrTheServer) {
  EXPECT_THAT(BreakingUnder("viewer-client",
                            [](const IncludeLine& i) {
                              return StartsWithAnyOf(i.header, {"capture-client/", "server/"});
                            }),
              IsEmpty());
}

}  // namespace
}  // namespace reenact::test_support
