// The viewer includes nothing of the capture client or the server (DESIGN.md): what both
// clients need lives in the libraries they share (common/, proto/, vision/, synthetic/).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/support/include_scan.h"

namespace reenact::test_support {
namespace {

using testing::IsEmpty;

TEST(ViewerDependencies, IncludesNothingOfTheCaptureClientOrTheServer) {
  const std::vector<IncludeLine> includes = IncludesUnder("viewer-client");
  ASSERT_GT(includes.size(), 10u);
  EXPECT_THAT(Breaking(includes,
                       [](const IncludeLine& i) {
                         return StartsWithAnyOf(i.header, {"capture-client/", "server/"});
                       }),
              IsEmpty());
}

}  // namespace
}  // namespace reenact::test_support
