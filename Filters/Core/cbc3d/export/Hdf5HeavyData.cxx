#include "cbc3d/export/Hdf5HeavyData.h"

#include <hdf5.h>

#include <vector>

namespace cbc3d
{
namespace
{
// Silences HDF5's error stack printing while alive (the errors come back as messages), and
// puts the caller's handler back after.
class QuietHdf5
{
public:
  QuietHdf5()
  {
    H5Eget_auto2(H5E_DEFAULT, &this->Function, &this->Data);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  ~QuietHdf5() { H5Eset_auto2(H5E_DEFAULT, this->Function, this->Data); }
  QuietHdf5(const QuietHdf5&) = delete;
  QuietHdf5& operator=(const QuietHdf5&) = delete;

private:
  H5E_auto2_t Function = nullptr;
  void* Data = nullptr;
};

// An HDF5 file being written: every call keeps the first error and turns later calls into
// no-ops; Close says whether the whole file reached the disk.
class Hdf5File
{
public:
  explicit Hdf5File(const std::string& name)
  {
    this->Links = H5Pcreate(H5P_LINK_CREATE);
    this->Datasets = H5Pcreate(H5P_DATASET_CREATE);
    if (this->Links < 0 || this->Datasets < 0 ||
      H5Pset_create_intermediate_group(this->Links, 1) < 0 ||
      H5Pset_obj_track_times(this->Datasets, false) < 0)
    {
      this->Error = "HDF5 property lists";
      return;
    }
    // In memory (the core driver, no backing store): HDF5 1.10 crashes, and loops at exit,
    // when a write to a full disk fails; the caller writes the image out.
    const hid_t access = H5Pcreate(H5P_FILE_ACCESS);
    if (access >= 0 && H5Pset_fapl_core(access, 1 << 20, false) >= 0)
      this->Id = H5Fcreate(name.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, access);
    if (access >= 0)
      H5Pclose(access);
    if (this->Id < 0)
      this->Error = "cannot create the HDF5 file in memory";
  }
  ~Hdf5File()
  {
    if (this->Id >= 0)
      H5Fclose(this->Id);
    if (this->Datasets >= 0)
      H5Pclose(this->Datasets);
    if (this->Links >= 0)
      H5Pclose(this->Links);
  }
  Hdf5File(const Hdf5File&) = delete;
  Hdf5File& operator=(const Hdf5File&) = delete;

  // A rows x columns dataset of `fileType` at `name`, written from `memoryType` values.
  template <typename T>
  void Put(const char* name, hid_t fileType, hid_t memoryType, const std::vector<T>& values,
    std::size_t columns)
  {
    if (!this->Error.empty())
      return;
    const hsize_t shape[2] = { values.size() / columns, columns };
    const hid_t space = H5Screate_simple(2, shape, nullptr);
    const hid_t set = space < 0
      ? -1
      : H5Dcreate2(this->Id, name, fileType, space, this->Links, this->Datasets, H5P_DEFAULT);
    if (set < 0 || H5Dwrite(set, memoryType, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) < 0)
      this->Error = std::string("cannot write the HDF5 dataset ") + name;
    if (set >= 0)
      H5Dclose(set);
    if (space >= 0)
      H5Sclose(space);
  }

  // Closes the file and gives its bytes in `image`; the error, if any step failed.
  std::string Close(std::string& image)
  {
    image.clear();
    if (this->Error.empty())
    {
      const ssize_t size = H5Fflush(this->Id, H5F_SCOPE_GLOBAL) < 0 ? -1 : H5Fget_file_image(this->Id, nullptr, 0);
      image.resize(size > 0 ? static_cast<std::size_t>(size) : 0);
      if (size <= 0 || H5Fget_file_image(this->Id, &image[0], image.size()) != size)
        this->Error = "cannot make the HDF5 file's image";
    }
    if (this->Id >= 0 && H5Fclose(this->Id) < 0 && this->Error.empty())
      this->Error = "cannot close the HDF5 file";
    this->Id = -1;
    return this->Error;
  }

private:
  hid_t Id = -1;
  hid_t Links = -1;
  hid_t Datasets = -1;
  std::string Error;
};

} // namespace

std::string MakeXdmfHeavyData(const TaggedMesh& mesh, std::string& image)
{
  const QuietHdf5 quiet;
  Hdf5File file("heavy-data.h5"); // a name for HDF5 alone: nothing is written there
  std::vector<std::int64_t> tets;
  tets.reserve(4 * mesh.Tets.size());
  for (const Tet& q : mesh.Tets)
  {
    for (const auto p : q)
      tets.push_back(static_cast<std::int64_t>(p));
  }
  file.Put(MeshTopology, H5T_STD_I64LE, H5T_NATIVE_INT64, tets, 4);
  std::vector<double> xyz;
  xyz.reserve(3 * mesh.Points.size());
  for (const Eigen::Vector3d& p : mesh.Points)
    xyz.insert(xyz.end(), { p.x(), p.y(), p.z() });
  file.Put(MeshGeometry, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, xyz, 3);
  std::vector<std::int32_t> tissues(mesh.Labels.size());
  for (std::size_t t = 0; t < mesh.Labels.size(); ++t)
    tissues[t] = static_cast<std::int32_t>(LabelValue(mesh, mesh.Labels[t]));
  file.Put(TissueValues, H5T_STD_I32LE, H5T_NATIVE_INT32, tissues, 1);
  if (!mesh.Triangles.empty())
  {
    std::vector<std::int64_t> triangles;
    triangles.reserve(3 * mesh.Triangles.size());
    for (const TaggedTriangle& t : mesh.Triangles)
    {
      for (const auto p : t.Points)
        triangles.push_back(static_cast<std::int64_t>(p));
    }
    file.Put(SurfaceTopology, H5T_STD_I64LE, H5T_NATIVE_INT64, triangles, 3);
    std::vector<std::int32_t> ids(mesh.Triangles.size());
    for (std::size_t s = 0; s < mesh.Surfaces.size(); ++s)
    {
      for (std::size_t t = mesh.SurfaceStart[s]; t < mesh.SurfaceStart[s + 1]; ++t)
        ids[t] = mesh.Surfaces[s].Id;
    }
    file.Put(SurfaceValues, H5T_STD_I32LE, H5T_NATIVE_INT32, ids, 1);
  }
  return file.Close(image);
}
} // namespace cbc3d
