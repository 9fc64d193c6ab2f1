// The Exodus II writer on three unit cubes in a row, tissues 1, 2, 1 (so the element blocks
// reorder the tets): written with WriteExportFile and read back with the netCDF C library. The
// blocks hold each tissue's tets, the side sets each surface's triangles as the (element, side)
// whose Exodus side nodes (1,2,4), (2,3,4), (1,4,3), (1,3,2) are the triangle's points in the
// triangle's (outward) orientation.
#include "TestMeshes.h"

#include "cbc3d/export/ExodusWriter.h"
#include "cbc3d/export/MeshExport.h"

#include <gtest/gtest.h>
#include <netcdf.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <sstream>
#include <unistd.h>

namespace
{
using namespace cbc3d;

TaggedMesh StripedCubes()
{
  const TetMesh mesh = cbc3d::testing::KuhnGrid(
    3, 1, 1, [](int, int, int) { return true; }, [](int x, int, int, int) { return x % 2 + 1; });
  TaggedMesh tagged;
  EXPECT_TRUE(BuildTaggedMesh(mesh, 0, tagged).IsOk());
  return tagged;
}

// A triangle turned to start at its smallest node, keeping its orientation.
std::array<int, 3> Rotated(std::array<int, 3> t)
{
  std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
  return t;
}

// A netCDF file open for reading, with the few reads the test needs.
struct Reader
{
  int Id = -1;
  explicit Reader(const std::string& path) { EXPECT_EQ(nc_open(path.c_str(), NC_NOWRITE, &Id), NC_NOERR); }
  ~Reader() { nc_close(Id); }

  std::size_t Dimension(const std::string& name) const
  {
    int dim = -1;
    std::size_t length = 0;
    EXPECT_EQ(nc_inq_dimid(Id, name.c_str(), &dim), NC_NOERR) << name;
    nc_inq_dimlen(Id, dim, &length);
    return length;
  }
  int Variable(const std::string& name) const
  {
    int var = -1;
    EXPECT_EQ(nc_inq_varid(Id, name.c_str(), &var), NC_NOERR) << name;
    return var;
  }
  std::vector<int> Ints(const std::string& name, std::size_t count) const
  {
    std::vector<int> values(count);
    EXPECT_EQ(nc_get_var_int(Id, Variable(name), values.data()), NC_NOERR) << name;
    return values;
  }
  std::vector<std::string> Names(const std::string& name, std::size_t count) const
  {
    const std::size_t length = Dimension("len_name");
    std::vector<char> text(count * length);
    EXPECT_EQ(nc_get_var_text(Id, Variable(name), text.data()), NC_NOERR) << name;
    std::vector<std::string> names;
    for (std::size_t i = 0; i < count; ++i)
      names.emplace_back(text.data() + i * length, strnlen(text.data() + i * length, length));
    return names;
  }
  std::string Text(int var, const std::string& name) const
  {
    std::size_t length = 0;
    EXPECT_EQ(nc_inq_attlen(Id, var, name.c_str(), &length), NC_NOERR) << name;
    std::string text(length, '\0');
    nc_get_att_text(Id, var, name.c_str(), text.data());
    return text;
  }
};

class ExodusWriter : public ::testing::Test
{
protected:
  void SetUp() override
  {
    char folder[] = "/tmp/cbc3d-exodus-XXXXXX";
    ASSERT_NE(mkdtemp(folder), nullptr);
    this->Folder = folder;
    this->Path = this->Folder + "/mesh.exo";
  }
  void TearDown() override
  {
    std::remove(this->Path.c_str());
    rmdir(this->Folder.c_str());
  }
  std::string Folder, Path;
};

TEST_F(ExodusWriter, BlocksPerTissueAndSideSetsPerSurface)
{
  const TaggedMesh mesh = StripedCubes();
  ASSERT_EQ(mesh.Tissues, (std::vector<std::int32_t>{ 1, 2 }));
  const Status status = WriteExportFile(mesh, this->Path);
  ASSERT_TRUE(status.IsOk()) << status.GetMessage();

  const Reader file(this->Path);
  EXPECT_EQ(file.Dimension("num_dim"), 3u);
  EXPECT_EQ(file.Dimension("num_nodes"), 16u);
  EXPECT_EQ(file.Dimension("num_elem"), 18u);
  EXPECT_EQ(file.Dimension("num_el_blk"), 2u);
  EXPECT_EQ(file.Dimension("num_side_sets"), 3u);
  EXPECT_EQ(file.Dimension("four"), 4u);
  EXPECT_EQ(file.Dimension("len_string"), 33u);
  EXPECT_EQ(file.Names("eb_names", 2), (std::vector<std::string>{ "tissue_1", "tissue_2" }));
  EXPECT_EQ(file.Ints("eb_prop1", 2), (std::vector<int>{ 1, 2 }));
  EXPECT_EQ(file.Names("ss_names", 3),
    (std::vector<std::string>{ "boundary_1", "boundary_2", "interface_1_2" }));
  EXPECT_EQ(file.Ints("ss_prop1", 3), (std::vector<int>{ 1, 2, 3 }));
  EXPECT_EQ(file.Text(NC_GLOBAL, "title"), "cbc3d multi-tissue tetrahedral mesh");

  // The elements, block after block, with their 1-based nodes and tissue.
  std::vector<std::array<int, 4>> elements;
  std::vector<int> tissue;
  for (int block = 1; block <= 2; ++block)
  {
    const std::string k = std::to_string(block);
    const std::size_t count = file.Dimension("num_el_in_blk" + k);
    EXPECT_EQ(count, block == 1 ? 12u : 6u);
    EXPECT_EQ(file.Dimension("num_nod_per_el" + k), 4u);
    EXPECT_EQ(file.Text(file.Variable("connect" + k), "elem_type"), "TETRA");
    const std::vector<int> connect = file.Ints("connect" + k, 4 * count);
    for (std::size_t e = 0; e < count; ++e)
    {
      elements.push_back({ connect[4 * e], connect[4 * e + 1], connect[4 * e + 2], connect[4 * e + 3] });
      tissue.push_back(block);
    }
  }
  // elem_num_map leads back to the mesh's tets.
  const std::vector<int> map = file.Ints("elem_num_map", 18);
  for (std::size_t e = 0; e < 18; ++e)
  {
    const Tet& tet = mesh.Tets[map[e] - 1];
    for (int k = 0; k < 4; ++k)
      EXPECT_EQ(elements[e][k], tet[k] + 1);
    EXPECT_EQ(mesh.Labels[map[e] - 1], tissue[e]);
  }

  const int sideNodes[5][3] = { {}, { 0, 1, 3 }, { 1, 2, 3 }, { 0, 3, 2 }, { 0, 2, 1 } };
  for (std::size_t s = 0; s < 3; ++s)
  {
    const std::string k = std::to_string(s + 1);
    const std::size_t count = file.Dimension("num_side_ss" + k);
    ASSERT_EQ(count, mesh.SurfaceStart[s + 1] - mesh.SurfaceStart[s]);
    const std::vector<int> element = file.Ints("elem_ss" + k, count);
    const std::vector<int> side = file.Ints("side_ss" + k, count);
    std::multiset<std::array<int, 3>> written, wanted;
    for (std::size_t i = 0; i < count; ++i)
    {
      ASSERT_TRUE(element[i] >= 1 && element[i] <= 18 && side[i] >= 1 && side[i] <= 4);
      std::array<int, 3> face;
      for (int c = 0; c < 3; ++c)
        face[c] = elements[element[i] - 1][sideNodes[side[i]][c]];
      written.insert(Rotated(face));
      EXPECT_EQ(tissue[element[i] - 1], mesh.Surfaces[s].Sides[0]) << mesh.Surfaces[s].Name;
      const TaggedTriangle& triangle = mesh.Triangles[mesh.SurfaceStart[s] + i];
      wanted.insert(Rotated(
        { int(triangle.Points[0] + 1), int(triangle.Points[1] + 1), int(triangle.Points[2] + 1) }));
    }
    EXPECT_EQ(written, wanted) << mesh.Surfaces[s].Name;
  }
  EXPECT_EQ(file.Dimension("num_side_ss3"), 4u); // two interfaces between the three cubes
}

TEST_F(ExodusWriter, OnlyToAFileAndNeverHalfWritten)
{
  std::ostringstream out;
  EXPECT_FALSE(WriteExport(StripedCubes(), ".exo", out).IsOk()); // netCDF needs a path
  EXPECT_TRUE(IsExportExtension(".exo"));
  EXPECT_FALSE(WriteExportFile(TaggedMesh(), this->Path).IsOk());
  EXPECT_NE(access(this->Path.c_str(), F_OK), 0); // no file, not even a partial one
  const Status missing = WriteExportFile(StripedCubes(), this->Folder + "/no/such/mesh.exo");
  EXPECT_FALSE(missing.IsOk());
  EXPECT_NE(missing.GetMessage().find("no/such/mesh.exo"), std::string::npos) << missing.GetMessage();
}
} // namespace
