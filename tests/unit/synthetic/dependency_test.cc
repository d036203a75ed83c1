// synthetic/ builds on common/, Eigen, the standard library and the glTF reader compiled into
// it (tinygltf with stb_image, synthetic/tinygltf_private.h) only: both clients and the
// evaluation link it, so it includes nothing of either client, the server, proto/ or vision/.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/support/include_scan.h"

namespace reenact::test_support {
namespace {

using testing::IsEmpty;

TEST(SyntheticDependencies, IncludesOnlyCommonSyntheticEigenGltfAndStd) {
  EXPECT_THAT(
      BreakingUnder("synthetic",
                    [](const IncludeLine& i) {
                      const bool gltf = i.header == "tiny_gltf.h" || i.header == "stb/stb_image.h";
                      return !(StartsWithAnyOf(i.header, {"common/", "synthetic/", "Eigen/"}) ||
                               gltf || IsStdHeader(i.header));
                    }),
      IsEmpty());
}

}  // namespace
}  // namespace reenact::test_support
