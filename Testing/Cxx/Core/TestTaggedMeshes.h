// A small tagged mesh with known surfaces, shared by the exporters' unit tests.
#ifndef cbc3d_TestTaggedMeshes_h
#define cbc3d_TestTaggedMeshes_h

#include "TestMeshes.h"

#include "cbc3d/base/TaggedMesh.h"

#include <gtest/gtest.h>

namespace cbc3d
{
namespace testing
{
// Two unit cubes side by side along x, labelled 1 and 2 (six Kuhn tets each), outside 0; with
// `codes`, those labels are codes of the values the writers write.
inline TaggedMesh TwoTaggedCubes(const LabelCodes& codes = LabelCodes(), std::int32_t outside = 0)
{
  const TetMesh mesh = KuhnGrid(
    2, 1, 1, [](int, int, int) { return true; }, [](int x, int, int, int) { return x + 1; });
  TaggedMesh tagged;
  EXPECT_TRUE(BuildTaggedMesh(mesh, outside, tagged, codes).IsOk());
  return tagged;
}
} // namespace testing
} // namespace cbc3d

#endif
