// The writers that need netCDF and HDF5 are loaded from libcbc3dBinaryFormats.so when first
// used (BinaryFormats.h): where the library is looked for, and that it is found and loaded once.
#include "cbc3d/export/BinaryFormats.h"
#include "cbc3d/export/ExodusWriter.h"

#include <gtest/gtest.h>

#include <dlfcn.h>

namespace
{
TEST(BinaryFormats, LooksBesideTheCallerThenInTheLibraryFolderThenByName)
{
  const std::vector<std::string> library = cbc3d::BinaryFormatsCandidates(
    "/opt/cbc3d/lib/libvtkCBC3DFilters.so", "lib");
  ASSERT_EQ(library.size(), 3u);
  EXPECT_EQ(library[0], "/opt/cbc3d/lib/libcbc3dBinaryFormats.so");
  EXPECT_EQ(library[1], "/opt/cbc3d/lib/../lib/libcbc3dBinaryFormats.so");
  EXPECT_EQ(library[2], "libcbc3dBinaryFormats.so");
  const std::vector<std::string> program =
    cbc3d::BinaryFormatsCandidates("/usr/local/bin/cbc3d", "lib64");
  EXPECT_EQ(program[0], "/usr/local/bin/libcbc3dBinaryFormats.so");
  EXPECT_EQ(program[1], "/usr/local/bin/../lib64/libcbc3dBinaryFormats.so");
  // A program started by a bare name from the current folder.
  EXPECT_EQ(cbc3d::BinaryFormatsCandidates("cbc3d", "lib")[1], "./../lib/libcbc3dBinaryFormats.so");
}

TEST(BinaryFormats, LoadsTheWritersOnceFromTheBuildTree)
{
  std::string error = "not cleared";
  const cbc3d::BinaryFormatWriters* writers = cbc3d::LoadBinaryFormatWriters(error);
  ASSERT_NE(writers, nullptr) << error;
  EXPECT_EQ(error, "");
  ASSERT_NE(writers->WriteExodus, nullptr);
  ASSERT_NE(writers->MakeXdmfHeavyData, nullptr);
  // The library's own functions, not copies: the same addresses as this program's link to them.
  EXPECT_EQ(writers->WriteExodus, &cbc3d::WriteExodus);
  EXPECT_EQ(cbc3d::LoadBinaryFormatWriters(error), writers);
  void* loaded = dlopen("libcbc3dBinaryFormats.so", RTLD_NOW | RTLD_NOLOAD);
  EXPECT_NE(loaded, nullptr) << "the library is loaded by its own name";
  if (loaded)
    dlclose(loaded);
}
} // namespace
