// The capture client includes nothing of the viewer or the server (DESIGN.md): what both
// clients need lives in the libraries they share (common/, proto/, vision/, synthetic/).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/support/include_scan.h"

namespace reenact::test_support {
namespace {

using testing::IsEmpty;

TEST(CaptureDependencies, IncludesNothingOfTheViewerOrTheServer) {
  EXPECT_THAT(BreakingUnder("capture-client",
                            [](const IncludeLine& i) {
                              return StartsWithAnyOf(i.header, {"viewer-client/", "server/"});
                            }),
              IsEmpty());
}

}  // namespace
}  // namespace reenact::test_support
