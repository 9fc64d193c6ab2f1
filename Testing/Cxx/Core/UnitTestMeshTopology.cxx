// Topology of meshes and of label images, on shapes whose answers are known by hand.
#include "cbc3d/quality/MeshTopology.h"
#include "TestMeshes.h"

#include <gtest/gtest.h>

#include <functional>
#include <random>
#include <set>
#include <utility>

namespace
{
using cbc3d::RegionTopology;

using cbc3d::testing::AddTet;
using cbc3d::testing::KuhnGrid;
using cbc3d::testing::OneTet;

void ExpectManifoldBall(const RegionTopology& r, std::int64_t triangles)
{
  EXPECT_EQ(r.FaceComponents, 1);
  EXPECT_EQ(r.VertexComponents, 1);
  EXPECT_EQ(r.HingedParts, 0);
  EXPECT_EQ(r.SurfaceTriangles, triangles);
  EXPECT_EQ(r.NonManifoldEdges, 0);
  EXPECT_EQ(r.NonManifoldVertices, 0);
  EXPECT_EQ(r.SurfaceEuler, 2);
}
} // namespace

TEST(MeshTopology, OneTetIsAManifoldBall)
{
  const cbc3d::MeshTopology topology = cbc3d::MeasureMeshTopology(OneTet());
  ExpectManifoldBall(topology.Whole, 4);
  ASSERT_EQ(topology.Tissues.size(), 1u);
  ExpectManifoldBall(topology.Tissues.at(1), 4);
  EXPECT_TRUE(topology.SolverReady());
}

TEST(MeshTopology, TwoTetsSharingAFaceAreOneBall)
{
  cbc3d::TetMesh mesh = OneTet();
  mesh.Points.emplace_back(1, 1, 1);
  AddTet(mesh, { 1, 2, 3, 4 });
  const cbc3d::MeshTopology topology = cbc3d::MeasureMeshTopology(mesh);
  ExpectManifoldBall(topology.Whole, 6); // V 5, E 9, F 6
  ExpectManifoldBall(topology.Tissues.at(1), 6);
  EXPECT_TRUE(topology.SolverReady());
}

TEST(MeshTopology, TwoTetsSharingAnEdgeAreHinged)
{
  cbc3d::TetMesh mesh = OneTet();
  // A second tet on the edge 0-1 only, on the other side in y and z.
  mesh.Points.emplace_back(0, -1, 0);
  mesh.Points.emplace_back(0, 0, -1);
  AddTet(mesh, { 0, 1, 4, 5 });
  const cbc3d::MeshTopology topology = cbc3d::MeasureMeshTopology(mesh);
  for (const RegionTopology& r : { topology.Whole, topology.Tissues.at(1) })
  {
    EXPECT_EQ(r.FaceComponents, 2);
    EXPECT_EQ(r.VertexComponents, 1);
    EXPECT_EQ(r.HingedParts, 1);
    EXPECT_EQ(r.SurfaceTriangles, 8);
    EXPECT_EQ(r.NonManifoldEdges, 1); // edge 0-1, in four triangles
    // At 0 and 1, the four triangles through the edge link both tets' triangles into one fan.
    EXPECT_EQ(r.NonManifoldVertices, 0);
    EXPECT_EQ(r.SurfaceEuler, 3); // V 6, E 11, F 8
  }
  EXPECT_FALSE(topology.SolverReady());
}

TEST(MeshTopology, TwoTetsSharingAVertexAreHinged)
{
  cbc3d::TetMesh mesh = OneTet();
  mesh.Points.emplace_back(-1, 0, 0);
  mesh.Points.emplace_back(0, -1, 0);
  mesh.Points.emplace_back(0, 0, -1);
  AddTet(mesh, { 0, 4, 5, 6 });
  const cbc3d::MeshTopology topology = cbc3d::MeasureMeshTopology(mesh);
  for (const RegionTopology& r : { topology.Whole, topology.Tissues.at(1) })
  {
    EXPECT_EQ(r.FaceComponents, 2);
    EXPECT_EQ(r.VertexComponents, 1);
    EXPECT_EQ(r.HingedParts, 1);
    EXPECT_EQ(r.NonManifoldEdges, 0);
    EXPECT_EQ(r.NonManifoldVertices, 1); // vertex 0: two fans of three triangles
    EXPECT_EQ(r.SurfaceEuler, 3);        // V 7, E 12, F 8
  }
  EXPECT_FALSE(topology.SolverReady());
}

TEST(MeshTopology, TwoSeparateTetsAreTwoComponentsNotHinged)
{
  cbc3d::TetMesh mesh = OneTet();
  for (int i = 0; i < 4; ++i)
    mesh.Points.push_back(mesh.Points[i] + Eigen::Vector3d(5, 0, 0));
  AddTet(mesh, { 4, 5, 6, 7 });
  const RegionTopology whole = cbc3d::MeasureMeshTopology(mesh).Whole;
  EXPECT_EQ(whole.FaceComponents, 2);
  EXPECT_EQ(whole.VertexComponents, 2);
  EXPECT_EQ(whole.HingedParts, 0);
  EXPECT_EQ(whole.SurfaceEuler, 4); // two spheres
}

TEST(MeshTopology, RingOfCubesIsASolidTorus)
{
  // 3 x 3 x 1 cubes without the centre one: 8 cubes, 48 tets.
  const cbc3d::TetMesh mesh = KuhnGrid(
    3, 3, 1, [](int x, int y, int) { return !(x == 1 && y == 1); }, [](int, int, int, int) { return 1; });
  ASSERT_EQ(mesh.Tets.size(), 48u);
  const cbc3d::MeshTopology topology = cbc3d::MeasureMeshTopology(mesh);
  const RegionTopology& r = topology.Whole;
  EXPECT_EQ(r.FaceComponents, 1);
  EXPECT_EQ(r.VertexComponents, 1);
  // Squares: 8 on top, 8 below, 12 outside, 4 inside the hole; two triangles each.
  EXPECT_EQ(r.SurfaceTriangles, 64);
  EXPECT_EQ(r.NonManifoldEdges, 0);
  EXPECT_EQ(r.NonManifoldVertices, 0);
  EXPECT_EQ(r.SurfaceEuler, 0);
  EXPECT_TRUE(topology.SolverReady());
}

TEST(MeshTopology, CubeOfTwoTissuesCountsTheInterfaceInBoth)
{
  // The six tets around the diagonal: three consecutive ones labelled 1, the other three 2.
  const cbc3d::TetMesh mesh = KuhnGrid(
    1, 1, 1, [](int, int, int) { return true; }, [](int, int, int, int t) { return t < 3 ? 1 : 2; });
  const cbc3d::MeshTopology topology = cbc3d::MeasureMeshTopology(mesh);
  ExpectManifoldBall(topology.Whole, 12); // the cube's 6 squares
  ASSERT_EQ(topology.Tissues.size(), 2u);
  // Each wedge: 12 tet faces, 2 pairs inside, so 8 surface triangles of which 2 are the
  // interface (V 6, E 12, F 8).
  ExpectManifoldBall(topology.Tissues.at(1), 8);
  ExpectManifoldBall(topology.Tissues.at(2), 8);
  EXPECT_TRUE(topology.SolverReady());
}

TEST(MeshTopology, HingedTissueInsideAManifoldBody)
{
  // Tets 0 and 3 of the cube share only the diagonal: tissue 2 is hinged, the body is not.
  const cbc3d::TetMesh mesh = KuhnGrid(
    1, 1, 1, [](int, int, int) { return true; }, [](int, int, int, int t) { return t == 0 || t == 3 ? 2 : 1; });
  for (const int threads : { 1, 3 }) // the edges and vertices are counted per thread, then summed
  {
    const cbc3d::MeshTopology topology = cbc3d::MeasureMeshTopology(mesh, threads);
    ExpectManifoldBall(topology.Whole, 12);
    for (const std::int32_t label : { 1, 2 })
    {
      const RegionTopology& r = topology.Tissues.at(label);
      EXPECT_EQ(r.FaceComponents, 2) << label;
      EXPECT_EQ(r.VertexComponents, 1) << label;
      EXPECT_EQ(r.NonManifoldEdges, 1) << label; // the diagonal
      // Two balls on one edge: tissue 2 V 6, E 11, F 8; tissue 1 (two wedges of two) V 8, E 17, F 12.
      EXPECT_EQ(r.SurfaceEuler, 3) << label;
    }
    EXPECT_FALSE(topology.SolverReady());
  }
}

TEST(MeshTopology, LargeBlockIsOneBall)
{
  // 50 x 50 x 40 cubes: 600,000 tets, the size the measure must handle quickly (on 4 threads).
  const int n[3] = { 50, 50, 40 };
  const cbc3d::TetMesh mesh = KuhnGrid(
    n[0], n[1], n[2], [](int, int, int) { return true; }, [](int x, int, int, int) { return x < 25 ? 1 : 2; });
  const cbc3d::MeshTopology topology = cbc3d::MeasureMeshTopology(mesh, 4);
  const std::int64_t squares = 2 * (n[0] * n[1] + n[1] * n[2] + n[2] * n[0]);
  ExpectManifoldBall(topology.Whole, 2 * squares);
  // Each half is a 25 x 50 x 40 block, the interface in both.
  const std::int64_t half = 2 * (25 * n[1] + n[1] * n[2] + n[2] * 25);
  ExpectManifoldBall(topology.Tissues.at(1), 2 * half);
  ExpectManifoldBall(topology.Tissues.at(2), 2 * half);
}

namespace
{
// An image of background 0 with `label` on the listed voxels.
cbc3d::LabelImage Voxels(std::array<int, 3> dimensions, const std::vector<std::array<int, 3>>& on, std::int32_t label = 1)
{
  cbc3d::LabelImage image;
  image.Dimensions = dimensions;
  image.Labels.assign(static_cast<std::size_t>(image.VoxelCount()), 0);
  for (const auto& v : on)
    image.Labels[image.VoxelIndex(v[0], v[1], v[2])] = label;
  return image;
}
} // namespace

TEST(ImageTopology, OneVoxelIsABall)
{
  const cbc3d::ImageTopology topology = cbc3d::MeasureImageTopology(Voxels({ 3, 3, 3 }, { { 1, 1, 1 } }));
  EXPECT_EQ(topology.WholeSurfaceEuler, 2);
  ASSERT_EQ(topology.TissueSurfaceEuler.size(), 1u);
  EXPECT_EQ(topology.TissueSurfaceEuler.at(1), 2);
}

TEST(ImageTopology, BlockFillingTheImageIsABall)
{
  // Beyond the image counts as outside: the faces on the border are surface too.
  cbc3d::LabelImage image = Voxels({ 2, 2, 2 }, {});
  image.Labels.assign(8, 1);
  EXPECT_EQ(cbc3d::ImageSurfaceEuler(image).at(1), 2);
}

TEST(ImageTopology, RingOfEightVoxelsIsATorus)
{
  std::vector<std::array<int, 3>> ring;
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 3; ++x)
      if (x != 1 || y != 1)
        ring.push_back({ x, y, 0 });
  EXPECT_EQ(cbc3d::ImageSurfaceEuler(Voxels({ 3, 3, 2 }, ring)).at(1), 0);
}

TEST(ImageTopology, HollowCubeIsAThickShell)
{
  cbc3d::LabelImage image = Voxels({ 3, 3, 3 }, {});
  image.Labels.assign(27, 1);
  image.Labels[image.VoxelIndex(1, 1, 1)] = 0;
  EXPECT_EQ(cbc3d::ImageSurfaceEuler(image).at(1), 4); // outer and inner sphere
}

TEST(ImageTopology, VoxelsTouchingAlongAnEdge)
{
  // V 8 + 8 - 2 = 14, E 12 + 12 - 1 = 23, F 12.
  EXPECT_EQ(cbc3d::ImageSurfaceEuler(Voxels({ 2, 2, 2 }, { { 0, 0, 0 }, { 1, 1, 0 } })).at(1), 3);
}

TEST(ImageTopology, VoxelsTouchingAtACorner)
{
  // V 8 + 8 - 1 = 15, E 24, F 12: two spheres glued at a point.
  EXPECT_EQ(cbc3d::ImageSurfaceEuler(Voxels({ 2, 2, 2 }, { { 0, 0, 0 }, { 1, 1, 1 } })).at(1), 3);
}

TEST(ImageTopology, TwoTissuesAndTheWholeBody)
{
  // Two face neighbours of different labels: each a ball, and so is their union. A third label
  // far away adds a sphere to the body.
  cbc3d::LabelImage image = Voxels({ 5, 2, 2 }, { { 0, 0, 0 } }, 1);
  image.Labels[image.VoxelIndex(1, 0, 0)] = 2;
  image.Labels[image.VoxelIndex(4, 1, 1)] = 7;
  const cbc3d::ImageTopology topology = cbc3d::MeasureImageTopology(image);
  EXPECT_EQ(topology.TissueSurfaceEuler.at(1), 2);
  EXPECT_EQ(topology.TissueSurfaceEuler.at(2), 2);
  EXPECT_EQ(topology.TissueSurfaceEuler.at(7), 2);
  EXPECT_EQ(topology.WholeSurfaceEuler, 4);
}

TEST(ImageTopology, BackgroundLabelsAreNotTissue)
{
  cbc3d::LabelImage image = Voxels({ 3, 3, 3 }, { { 1, 1, 1 } }, 5);
  image.BackgroundLabels = { 0, 5 };
  const cbc3d::ImageTopology topology = cbc3d::MeasureImageTopology(image);
  EXPECT_TRUE(topology.TissueSurfaceEuler.empty());
  EXPECT_EQ(topology.WholeSurfaceEuler, 0);
}

namespace
{
// The voxel-face surface's V - E + F counted the long way: every face between a selected voxel
// and one that is not (or the image's outside), its corners and edges collected in sets.
std::int64_t EulerByEnumeration(const cbc3d::LabelImage& image, const std::function<bool(std::int32_t)>& selected)
{
  const auto& d = image.Dimensions;
  auto in = [&](int i, int j, int k) {
    return i >= 0 && j >= 0 && k >= 0 && i < d[0] && j < d[1] && k < d[2] && selected(image.LabelAt(i, j, k));
  };
  std::set<std::array<int, 3>> corners;
  std::set<std::array<int, 4>> edges; // lower corner and axis
  std::int64_t faces = 0;
  for (int k = 0; k < d[2]; ++k)
    for (int j = 0; j < d[1]; ++j)
      for (int i = 0; i < d[0]; ++i)
        for (int a = 0; a < 3 && in(i, j, k); ++a)
          for (const int side : { 0, 1 })
          {
            std::array<int, 3> n = { i, j, k };
            n[a] += side ? 1 : -1;
            if (in(n[0], n[1], n[2]))
              continue;
            ++faces;
            const int b = (a + 1) % 3, c = (a + 2) % 3;
            std::array<int, 3> origin = { i, j, k };
            origin[a] += side;
            for (const int db : { 0, 1 })
              for (const int dc : { 0, 1 })
              {
                std::array<int, 3> corner = origin;
                corner[b] += db;
                corner[c] += dc;
                corners.insert(corner);
              }
            for (const int offset : { 0, 1 })
            {
              std::array<int, 3> alongB = origin, alongC = origin;
              alongB[c] += offset; // the edges along b at c = 0 and 1
              alongC[b] += offset;
              edges.insert({ alongB[0], alongB[1], alongB[2], b });
              edges.insert({ alongC[0], alongC[1], alongC[2], c });
            }
          }
  return std::int64_t(corners.size()) - std::int64_t(edges.size()) + faces;
}
} // namespace

TEST(ImageTopology, RandomImagesMatchCountingEveryFace)
{
  std::mt19937 random(12345);
  for (int trial = 0; trial < 60; ++trial)
  {
    const std::array<int, 3> dimensions = { 2 + int(random() % 6), 2 + int(random() % 6), 2 + int(random() % 7) };
    cbc3d::LabelImage image = Voxels(dimensions, {});
    const int density = 1 + int(random() % 4); // in 5: from sparse specks to nearly solid
    for (auto& label : image.Labels)
      label = int(random() % 5) < density ? 1 + int(random() % 3) : 0;
    const int threads = 1 + trial % 3; // the slabs split differently
    const cbc3d::ImageTopology topology = cbc3d::MeasureImageTopology(image, threads);
    for (const auto& [label, euler] : topology.TissueSurfaceEuler)
    {
      EXPECT_EQ(euler, EulerByEnumeration(image, [label = label](std::int32_t l) { return l == label; }))
        << "trial " << trial << ", label " << label;
    }
    EXPECT_EQ(topology.WholeSurfaceEuler, EulerByEnumeration(image, [](std::int32_t l) { return l != 0; }))
      << "trial " << trial;
  }
}

namespace
{
// The two manifold readings counted from their definitions. Joined: twice V - E + F - C of the
// union of closed voxels (every corner, edge and face of a selected voxel, collected in sets).
// Parted: twice V - E + F - C of the voxels joined through faces (voxels, face-neighbour pairs,
// 2 x 2 squares and 2 x 2 x 2 cubes all selected).
std::array<std::int64_t, 2> ManifoldReadingsByEnumeration(
  const cbc3d::LabelImage& image, const std::function<bool(std::int32_t)>& selected)
{
  const auto& d = image.Dimensions;
  auto in = [&](int i, int j, int k) {
    return i >= 0 && j >= 0 && k >= 0 && i < d[0] && j < d[1] && k < d[2] && selected(image.LabelAt(i, j, k));
  };
  std::set<std::array<int, 3>> corners;
  std::set<std::array<int, 4>> edges, faces; // lower corner and axis (of the edge; across the face)
  std::int64_t cubes = 0, pairs = 0, squares = 0, blocks = 0;
  for (int k = -1; k < d[2]; ++k)
    for (int j = -1; j < d[1]; ++j)
      for (int i = -1; i < d[0]; ++i)
      {
        if (in(i, j, k))
        {
          ++cubes;
          for (int c = 0; c < 8; ++c)
            corners.insert({ i + (c & 1), j + (c >> 1 & 1), k + (c >> 2) });
          for (int a = 0; a < 3; ++a)
            for (int u = 0; u < 2; ++u)
              for (int v = 0; v < 2; ++v)
              {
                std::array<int, 3> at = { i, j, k };
                at[(a + 1) % 3] += u;
                at[(a + 2) % 3] += v;
                edges.insert({ at[0], at[1], at[2], a });
                std::array<int, 3> face = { i, j, k };
                face[a] += u;
                faces.insert({ face[0], face[1], face[2], a });
              }
        }
        // The parted complex's cells whose lowest voxel is (i, j, k).
        const bool here = in(i, j, k);
        pairs += here && in(i + 1, j, k);
        pairs += here && in(i, j + 1, k);
        pairs += here && in(i, j, k + 1);
        squares += here && in(i + 1, j, k) && in(i, j + 1, k) && in(i + 1, j + 1, k);
        squares += here && in(i + 1, j, k) && in(i, j, k + 1) && in(i + 1, j, k + 1);
        squares += here && in(i, j + 1, k) && in(i, j, k + 1) && in(i, j + 1, k + 1);
        bool block = true;
        for (int c = 0; c < 8; ++c)
          block = block && in(i + (c & 1), j + (c >> 1 & 1), k + (c >> 2));
        blocks += block;
      }
  const std::int64_t joined = std::int64_t(corners.size()) - std::int64_t(edges.size()) + std::int64_t(faces.size()) - cubes;
  const std::int64_t parted = cubes - pairs + squares - blocks;
  return { 2 * joined, 2 * parted };
}
} // namespace

TEST(ImageTopology, PinchesJoinedOrPartedAroundTheVoxelFaceFigure)
{
  // Two voxels touching along an edge, or at a corner: a bridge (one ball) or two balls.
  for (const std::array<int, 3> other : { std::array<int, 3>{ 1, 1, 0 }, std::array<int, 3>{ 1, 1, 1 } })
  {
    const cbc3d::ImageTopology topology = cbc3d::MeasureImageTopology(Voxels({ 2, 2, 2 }, { { 0, 0, 0 }, other }));
    EXPECT_EQ(topology.TissueSurfaceEuler.at(1), 3);
    EXPECT_EQ(topology.TissuePinchesJoinedEuler(1), 2);
    EXPECT_EQ(topology.TissuePinchesPartedEuler.at(1), 4);
    EXPECT_EQ(topology.WholePinchesJoinedEuler(), 2);
    EXPECT_EQ(topology.WholePinchesPartedEuler, 4);
  }
  // Without a pinch the three agree: a solid torus of 8 voxels.
  std::vector<std::array<int, 3>> ring;
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 3; ++x)
      if (x != 1 || y != 1)
        ring.push_back({ x, y, 0 });
  const cbc3d::ImageTopology torus = cbc3d::MeasureImageTopology(Voxels({ 3, 3, 2 }, ring));
  EXPECT_EQ(torus.TissuePinchesJoinedEuler(1), 0);
  EXPECT_EQ(torus.TissuePinchesPartedEuler.at(1), 0);
  // Four voxels round the middle one of a 3 x 3 slice, each touching the next along an edge:
  // joined, a ring (a torus); parted, four separate voxels.
  const cbc3d::ImageTopology square =
    cbc3d::MeasureImageTopology(Voxels({ 3, 3, 1 }, { { 1, 0, 0 }, { 0, 1, 0 }, { 2, 1, 0 }, { 1, 2, 0 } }));
  EXPECT_EQ(square.TissuePinchesJoinedEuler(1), 0); // a ring round the middle voxel
  EXPECT_EQ(square.TissuePinchesPartedEuler.at(1), 8); // four separate voxels
  EXPECT_EQ(square.TissueSurfaceEuler.at(1), 4);
}

TEST(ImageTopology, RandomImagesManifoldReadingsMatchTheirDefinitions)
{
  std::mt19937 random(777);
  for (int trial = 0; trial < 60; ++trial)
  {
    const std::array<int, 3> dimensions = { 2 + int(random() % 6), 2 + int(random() % 6), 2 + int(random() % 7) };
    cbc3d::LabelImage image = Voxels(dimensions, {});
    const int density = 1 + int(random() % 4);
    for (auto& label : image.Labels)
      label = int(random() % 5) < density ? 1 + int(random() % 3) : 0;
    const cbc3d::ImageTopology topology = cbc3d::MeasureImageTopology(image, 1 + trial % 3);
    for (const auto& [label, euler] : topology.TissueSurfaceEuler)
    {
      const auto readings = ManifoldReadingsByEnumeration(image, [label = label](std::int32_t l) { return l == label; });
      EXPECT_EQ(topology.TissuePinchesJoinedEuler(label), readings[0]) << "trial " << trial << ", label " << label;
      EXPECT_EQ(topology.TissuePinchesPartedEuler.at(label), readings[1]) << "trial " << trial << ", label " << label;
    }
    const auto whole = ManifoldReadingsByEnumeration(image, [](std::int32_t l) { return l != 0; });
    EXPECT_EQ(topology.WholePinchesJoinedEuler(), whole[0]) << "trial " << trial;
    EXPECT_EQ(topology.WholePinchesPartedEuler, whole[1]) << "trial " << trial;
  }
}
