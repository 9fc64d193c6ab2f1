#include "cbc3d/XdmfWriter.h"

#include "cbc3d/AtomicFile.h"
#include "cbc3d/MeshExport.h"
#include "cbc3d/PendingFiles.h"

#include <hdf5.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <unistd.h>
#include <vector>

namespace cbc3d
{
namespace
{
// The datasets of the .h5, as dolfinx's XDMFFile names them.
constexpr const char* MeshTopology = "/Mesh/mesh/topology";
constexpr const char* MeshGeometry = "/Mesh/mesh/geometry";
constexpr const char* TissueValues = "/MeshTags/tissues/Values";
constexpr const char* SurfaceTopology = "/MeshTags/surfaces/topology";
constexpr const char* SurfaceValues = "/MeshTags/surfaces/Values";

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
    // when a write to a full disk fails; the image is written out by WriteFileBytes.
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

  // Closes the file and writes its image to `path`; the error, if any step failed.
  std::string Close(const std::string& path)
  {
    std::string image;
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
    if (this->Error.empty())
      WriteFileBytes(path, image, this->Error);
    return this->Error;
  }

private:
  hid_t Id = -1;
  hid_t Links = -1;
  hid_t Datasets = -1;
  std::string Error;
};

std::string WriteHeavyData(const TaggedMesh& mesh, const std::string& path)
{
  const QuietHdf5 quiet;
  Hdf5File file(path);
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
  return file.Close(path);
}

// `text` with XML's special characters escaped (a file name in a DataItem).
std::string EscapeXml(const std::string& text)
{
  std::string escaped;
  for (const char c : text)
  {
    switch (c)
    {
      case '&': escaped += "&amp;"; break;
      case '<': escaped += "&lt;"; break;
      case '>': escaped += "&gt;"; break;
      default: escaped += c;
    }
  }
  return escaped;
}

// A DataItem naming the dataset `set` of the .h5.
std::string HeavyItem(const std::string& h5, const char* set, std::size_t rows,
  std::size_t columns, bool integers)
{
  std::ostringstream item;
  item << "<DataItem Dimensions=\"" << rows << " " << columns << "\""
       << (integers ? " NumberType=\"Int\"" : "") << " Format=\"HDF\">" << h5 << ":" << set
       << "</DataItem>\n";
  return item.str();
}

void WriteLightData(const TaggedMesh& mesh, const std::string& h5, std::ostream& out)
{
  const std::size_t tets = mesh.Tets.size(), triangles = mesh.Triangles.size();
  const std::string tetTopology = "      <Topology TopologyType=\"Tetrahedron\" NumberOfElements=\"" +
    std::to_string(tets) + "\" NodesPerElement=\"4\">\n        " +
    HeavyItem(h5, MeshTopology, tets, 4, true) + "      </Topology>\n";
  const char* geometry = "      <xi:include xpointer=\"xpointer(/Xdmf/Domain/Grid/Geometry)\" />\n";
  out << "<?xml version=\"1.0\"?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
      << "<Xdmf Version=\"3.0\" xmlns:xi=\"http://www.w3.org/2001/XInclude\">\n  <Domain>\n"
      << "    <Grid Name=\"mesh\" GridType=\"Uniform\">\n"
      << tetTopology << "      <Geometry GeometryType=\"XYZ\">\n        "
      << HeavyItem(h5, MeshGeometry, mesh.Points.size(), 3, false)
      << "      </Geometry>\n    </Grid>\n";
  out << "    <Grid Name=\"tissues\" GridType=\"Uniform\">\n"
      << geometry << tetTopology
      << "      <Attribute Name=\"tissues\" AttributeType=\"Scalar\" Center=\"Cell\">\n        "
      << HeavyItem(h5, TissueValues, tets, 1, true) << "      </Attribute>\n    </Grid>\n";
  if (triangles > 0)
  {
    out << "    <Grid Name=\"surfaces\" GridType=\"Uniform\">\n"
        << geometry << "      <Topology TopologyType=\"Triangle\" NumberOfElements=\""
        << triangles << "\" NodesPerElement=\"3\">\n        "
        << HeavyItem(h5, SurfaceTopology, triangles, 3, true) << "      </Topology>\n"
        << "      <Attribute Name=\"surfaces\" AttributeType=\"Scalar\" Center=\"Cell\">\n        "
        << HeavyItem(h5, SurfaceValues, triangles, 1, true)
        << "      </Attribute>\n    </Grid>\n";
  }
  out << "  </Domain>\n</Xdmf>\n";
}

std::string FileName(const std::string& path)
{
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}
} // namespace

std::string XdmfHeavyDataPath(const std::string& path)
{
  const std::size_t slash = path.find_last_of('/');
  const std::size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash))
    return path + ".h5";
  return path.substr(0, dot) + ".h5";
}

Status WriteXdmf(const TaggedMesh& mesh, const std::string& path)
{
  if (mesh.Tets.empty())
    return Status::Error("the mesh has no tetrahedra to write");
  const Status fits = RequireInt32Tissues(mesh, "XDMF", "dolfinx's mesh tags are 32-bit integers");
  if (!fits.IsOk())
    return fits;
  const std::string h5 = XdmfHeavyDataPath(path);
  const std::string xdmfPart = TemporaryPath(path), h5Part = TemporaryPath(h5);
  const int xdmfSlot = PendingFiles::Add(xdmfPart), h5Slot = PendingFiles::Add(h5Part);
  const auto done = [&](const std::string& why) {
    if (!why.empty())
    {
      std::remove(xdmfPart.c_str());
      std::remove(h5Part.c_str());
    }
    PendingFiles::Forget(xdmfSlot);
    PendingFiles::Forget(h5Slot);
    return why.empty() ? Status::Ok() : Status::Error(why);
  };

  std::string error = WriteHeavyData(mesh, h5Part);
  if (!error.empty())
    return done("'" + h5 + "': " + error);
  {
    std::ostringstream out;
    WriteLightData(mesh, EscapeXml(FileName(h5)), out);
    if (!WriteFileBytes(xdmfPart, out.str(), error))
      return done(error);
  }
  if (!MoveIntoPlace(h5Part, h5, error))
    return done(error);
  if (!MoveIntoPlace(xdmfPart, path, error))
  {
    std::remove(h5.c_str()); // no .h5 without its .xdmf
    return done(error);
  }
  return done("");
}
} // namespace cbc3d
