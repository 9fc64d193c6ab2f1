// The XDMF writer on two unit cubes of tissues 1 and 2 (12 points, 12 tets, 22 triangles:
// boundary_1 and boundary_2 of 10, interface_1_2 of 2): written with WriteExportFile as
// mesh.xdmf and mesh.h5, the .h5 read back with the HDF5 C library (dolfinx's datasets, the
// mesh's points, tets, labels, triangles and surface ids), the .xdmf naming them; the same mesh
// gives the same bytes; and a failed write (no stream, no folder, an unwritable folder, the
// .xdmf's name taken by a folder) leaves neither file nor a temporary one.
#include "TestMeshes.h"
#include "TestTaggedMeshes.h"

#include "cbc3d/export/MeshExport.h"
#include "cbc3d/export/XdmfWriter.h"

#include <gtest/gtest.h>
#include <hdf5.h>

#include <dirent.h>
#include <fstream>
#include <sstream>
#include <sys/stat.h>
#include <unistd.h>

namespace
{
using namespace cbc3d;

std::string Read(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::size_t Count(const std::string& text, const std::string& word)
{
  std::size_t n = 0;
  for (std::size_t at = text.find(word); at != std::string::npos; at = text.find(word, at + 1))
    ++n;
  return n;
}

// The names in a folder, but . and ..
std::vector<std::string> Listing(const std::string& folder)
{
  std::vector<std::string> names;
  if (DIR* dir = opendir(folder.c_str()))
  {
    while (const dirent* entry = readdir(dir))
    {
      const std::string name = entry->d_name;
      if (name != "." && name != "..")
        names.push_back(name);
    }
    closedir(dir);
  }
  return names;
}

// A dataset of the .h5 read as `memoryType`, with its shape.
template <typename T>
std::vector<T> Dataset(hid_t file, const char* name, hid_t memoryType, std::vector<hsize_t>& shape)
{
  const hid_t set = H5Dopen2(file, name, H5P_DEFAULT);
  EXPECT_GE(set, 0) << name;
  if (set < 0)
    return {};
  const hid_t space = H5Dget_space(set);
  shape.assign(static_cast<std::size_t>(H5Sget_simple_extent_ndims(space)), 0);
  H5Sget_simple_extent_dims(space, shape.data(), nullptr);
  std::vector<T> values(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space)));
  EXPECT_GE(H5Dread(set, memoryType, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), 0) << name;
  H5Sclose(space);
  H5Dclose(set);
  return values;
}

class XdmfWriter : public ::testing::Test
{
protected:
  void SetUp() override
  {
    char folder[] = "/tmp/cbc3d-xdmf-XXXXXX";
    ASSERT_NE(mkdtemp(folder), nullptr);
    this->Folder = folder;
    this->Path = this->Folder + "/mesh.xdmf";
  }
  void TearDown() override
  {
    chmod(this->Folder.c_str(), 0700);
    for (const std::string& name : Listing(this->Folder))
    {
      const std::string path = this->Folder + "/" + name;
      if (std::remove(path.c_str()) != 0)
        rmdir(path.c_str());
    }
    rmdir(this->Folder.c_str());
  }
  std::string Folder, Path;
};

TEST_F(XdmfWriter, MeshAndTagsInTheH5Beside)
{
  const TaggedMesh mesh = cbc3d::testing::TwoTaggedCubes();
  EXPECT_EQ(XdmfHeavyDataPath(this->Path), this->Folder + "/mesh.h5");
  EXPECT_EQ(XdmfHeavyDataPath("a.b/mesh"), "a.b/mesh.h5");
  const Status status = WriteExportFile(mesh, this->Path);
  ASSERT_TRUE(status.IsOk()) << status.GetMessage();
  EXPECT_EQ(Listing(this->Folder).size(), 2u); // mesh.xdmf and mesh.h5, no temporary left

  const std::string text = Read(this->Path);
  EXPECT_NE(text.find("<Grid Name=\"mesh\""), std::string::npos);
  EXPECT_NE(text.find("<Grid Name=\"tissues\""), std::string::npos);
  EXPECT_NE(text.find("<Grid Name=\"surfaces\""), std::string::npos);
  EXPECT_NE(text.find("TopologyType=\"Triangle\" NumberOfElements=\"22\""), std::string::npos);
  EXPECT_EQ(Count(text, "TopologyType=\"Tetrahedron\" NumberOfElements=\"12\""), 2u);
  EXPECT_EQ(Count(text, "Format=\"HDF\">mesh.h5:/"), 6u); // the file's name alone
  EXPECT_EQ(Count(text, "Format=\"XML\""), 0u);
  for (const char* item : { "\"12 4\" NumberType=\"Int\" Format=\"HDF\">mesh.h5:/Mesh/mesh/topology<",
         "\"12 3\" Format=\"HDF\">mesh.h5:/Mesh/mesh/geometry<",
         "\"12 1\" NumberType=\"Int\" Format=\"HDF\">mesh.h5:/MeshTags/tissues/Values<",
         "\"22 3\" NumberType=\"Int\" Format=\"HDF\">mesh.h5:/MeshTags/surfaces/topology<",
         "\"22 1\" NumberType=\"Int\" Format=\"HDF\">mesh.h5:/MeshTags/surfaces/Values<" })
    EXPECT_NE(text.find(item), std::string::npos) << item;

  const hid_t file = H5Fopen((this->Folder + "/mesh.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  std::vector<hsize_t> shape;
  const auto tets = Dataset<std::int64_t>(file, "/Mesh/mesh/topology", H5T_NATIVE_INT64, shape);
  EXPECT_EQ(shape, (std::vector<hsize_t>{ 12, 4 }));
  for (std::size_t t = 0; t < mesh.Tets.size() && 4 * t + 3 < tets.size(); ++t)
    for (int k = 0; k < 4; ++k)
      EXPECT_EQ(tets[4 * t + k], mesh.Tets[t][k]);
  const auto xyz = Dataset<double>(file, "/Mesh/mesh/geometry", H5T_NATIVE_DOUBLE, shape);
  EXPECT_EQ(shape, (std::vector<hsize_t>{ 12, 3 }));
  for (std::size_t p = 0; p < mesh.Points.size() && 3 * p + 2 < xyz.size(); ++p)
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(xyz[3 * p + k], mesh.Points[p][k]);
  const auto labels = Dataset<std::int32_t>(file, "/MeshTags/tissues/Values", H5T_NATIVE_INT32, shape);
  EXPECT_EQ(shape, (std::vector<hsize_t>{ 12, 1 }));
  EXPECT_EQ(labels, mesh.Labels);
  const auto triangles =
    Dataset<std::int64_t>(file, "/MeshTags/surfaces/topology", H5T_NATIVE_INT64, shape);
  EXPECT_EQ(shape, (std::vector<hsize_t>{ 22, 3 }));
  for (std::size_t t = 0; t < mesh.Triangles.size() && 3 * t + 2 < triangles.size(); ++t)
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(triangles[3 * t + k], mesh.Triangles[t].Points[k]);
  const auto ids = Dataset<std::int32_t>(file, "/MeshTags/surfaces/Values", H5T_NATIVE_INT32, shape);
  EXPECT_EQ(shape, (std::vector<hsize_t>{ 22, 1 }));
  std::vector<std::int32_t> wanted;
  for (std::size_t s = 0; s < mesh.Surfaces.size(); ++s)
    wanted.insert(wanted.end(), mesh.SurfaceStart[s + 1] - mesh.SurfaceStart[s], mesh.Surfaces[s].Id);
  EXPECT_EQ(ids, wanted);
  H5Fclose(file);

  // The same mesh, the same bytes (no time stamps in the .h5), under another name.
  const std::string h5 = Read(this->Folder + "/mesh.h5");
  ASSERT_TRUE(WriteExportFile(mesh, this->Folder + "/again.XDMF").IsOk());
  EXPECT_EQ(Read(this->Folder + "/again.h5"), h5);
  std::string renamed = text;
  for (std::size_t at = renamed.find("mesh.h5:"); at != std::string::npos;
       at = renamed.find("mesh.h5:", at))
    renamed.replace(at, 4, "again");
  EXPECT_EQ(Read(this->Folder + "/again.XDMF"), renamed);
}

TEST_F(XdmfWriter, OnlyToFilesAndNeverHalfWritten)
{
  std::ostringstream out;
  EXPECT_FALSE(WriteExport(cbc3d::testing::TwoTaggedCubes(), ".xdmf", out).IsOk()); // HDF5 needs a path
  EXPECT_TRUE(IsExportExtension(".xdmf"));
  EXPECT_FALSE(WriteExportFile(TaggedMesh(), this->Path).IsOk());
  EXPECT_TRUE(Listing(this->Folder).empty());
  const Status missing = WriteExportFile(cbc3d::testing::TwoTaggedCubes(), this->Folder + "/no/such/mesh.xdmf");
  EXPECT_FALSE(missing.IsOk());
  EXPECT_NE(missing.GetMessage().find("no/such/mesh.xdmf"), std::string::npos)
    << missing.GetMessage();

  // The .xdmf's name taken by a folder: the .h5 is written and renamed, the .xdmf's rename
  // fails, and the .h5 goes again.
  ASSERT_EQ(mkdir(this->Path.c_str(), 0700), 0);
  EXPECT_FALSE(WriteExportFile(cbc3d::testing::TwoTaggedCubes(), this->Path).IsOk());
  EXPECT_EQ(Listing(this->Folder), (std::vector<std::string>{ "mesh.xdmf" }));
  rmdir(this->Path.c_str());

  if (geteuid() != 0) // root writes anywhere
  {
    ASSERT_EQ(chmod(this->Folder.c_str(), 0500), 0);
    const Status unwritable = WriteExportFile(cbc3d::testing::TwoTaggedCubes(), this->Path);
    chmod(this->Folder.c_str(), 0700);
    EXPECT_FALSE(unwritable.IsOk());
    EXPECT_TRUE(Listing(this->Folder).empty());
  }
}
} // namespace
