#include "cbc3d/export/ExodusWriter.h"

#include <netcdf.h>

#include <algorithm>
#include <climits>
#include <sstream>

namespace cbc3d
{
namespace
{
// The version the file claims (the attributes api_version and version, as Exodus's library
// writes them), and the shortest name length Exodus allows for (32 characters and a null).
constexpr float ExodusVersion = 8.0f;
constexpr std::size_t NameLength = 33;

// A netCDF file being written: every call goes through Check, which keeps the first error
// (with the call that failed) and turns every later call into a no-op.
class NetcdfFile
{
public:
  explicit NetcdfFile(const std::string& path)
  {
    const int code = nc_create(path.c_str(), NC_CLOBBER | NC_64BIT_OFFSET, &this->Id);
    this->Open = code == NC_NOERR;
    this->Check(code, "create");
  }
  ~NetcdfFile()
  {
    if (this->Open)
      nc_abort(this->Id);
  }
  NetcdfFile(const NetcdfFile&) = delete;
  NetcdfFile& operator=(const NetcdfFile&) = delete;

  bool Ok() const { return this->Error.empty(); }

  void Check(int code, const std::string& what)
  {
    if (code != NC_NOERR && this->Error.empty())
      this->Error = what + ": " + nc_strerror(code);
  }

  int Dimension(const std::string& name, std::size_t length)
  {
    int id = -1;
    if (this->Ok())
      this->Check(nc_def_dim(this->Id, name.c_str(), length, &id), "dimension " + name);
    return id;
  }

  int Variable(const std::string& name, nc_type type, std::vector<int> dimensions)
  {
    int id = -1;
    if (this->Ok())
      this->Check(nc_def_var(this->Id, name.c_str(), type, static_cast<int>(dimensions.size()),
                    dimensions.data(), &id),
        "variable " + name);
    return id;
  }

  void Text(int variable, const std::string& name, const std::string& value)
  {
    if (this->Ok())
      this->Check(nc_put_att_text(this->Id, variable, name.c_str(), value.size(), value.c_str()),
        "attribute " + name);
  }

  void Int(int variable, const std::string& name, int value)
  {
    if (this->Ok())
      this->Check(nc_put_att_int(this->Id, variable, name.c_str(), NC_INT, 1, &value),
        "attribute " + name);
  }

  void Float(int variable, const std::string& name, float value)
  {
    if (this->Ok())
      this->Check(nc_put_att_float(this->Id, variable, name.c_str(), NC_FLOAT, 1, &value),
        "attribute " + name);
  }

  void EndDefinitions()
  {
    if (this->Ok())
      this->Check(nc_enddef(this->Id), "end of definitions");
  }

  void Put(int variable, const std::vector<int>& values)
  {
    if (this->Ok())
      this->Check(nc_put_var_int(this->Id, variable, values.data()), "ints");
  }

  void Put(int variable, const std::vector<double>& values)
  {
    if (this->Ok())
      this->Check(nc_put_var_double(this->Id, variable, values.data()), "doubles");
  }

  void Put(int variable, const std::vector<char>& values)
  {
    if (this->Ok())
      this->Check(nc_put_var_text(this->Id, variable, values.data()), "names");
  }

  // Closes the file (writing it out); the error, if any call failed.
  std::string Close()
  {
    if (this->Open)
    {
      this->Open = false;
      if (this->Ok())
        this->Check(nc_close(this->Id), "close");
      else
        nc_abort(this->Id);
    }
    return this->Error;
  }

private:
  int Id = -1;
  bool Open = false;
  std::string Error;
};

// Names as a (count, length) char array, each padded with nulls.
std::vector<char> NameArray(const std::vector<std::string>& names, std::size_t length)
{
  std::vector<char> array(names.size() * length, '\0');
  for (std::size_t i = 0; i < names.size(); ++i)
    std::copy(names[i].begin(), names[i].end(), array.begin() + i * length);
  return array;
}

// The block ids: the tissue labels when all are positive and fit the file's 32-bit ids (Exodus
// ids are positive), else 1, 2, ...; the block names carry the labels either way.
std::vector<int> BlockIds(const TaggedMesh& mesh)
{
  std::vector<int> ids;
  bool labelsFit = true;
  for (const std::int32_t tissue : mesh.Tissues)
  {
    const std::int64_t value = LabelValue(mesh, tissue);
    labelsFit = labelsFit && value > 0 && FitsInt32(value);
    ids.push_back(static_cast<int>(value));
  }
  if (!labelsFit)
  {
    for (std::size_t b = 0; b < ids.size(); ++b)
      ids[b] = static_cast<int>(b + 1);
  }
  return ids;
}

struct Definitions
{
  int CoordX = -1, CoordY = -1, CoordZ = -1, CoordNames = -1, ElementMap = -1;
  int BlockStatus = -1, BlockIds = -1, BlockNames = -1;
  int SideStatus = -1, SideIds = -1, SideNames = -1;
  std::vector<int> Connect, SideElements, SideSides;
};

Definitions Define(NetcdfFile& file, const TaggedMesh& mesh,
  const std::vector<std::size_t>& blockSizes, std::size_t nameLength)
{
  Definitions d;
  file.Text(NC_GLOBAL, "title", "cbc3d multi-tissue tetrahedral mesh");
  file.Float(NC_GLOBAL, "api_version", ExodusVersion);
  file.Float(NC_GLOBAL, "version", ExodusVersion);
  file.Int(NC_GLOBAL, "floating_point_word_size", 8);
  file.Int(NC_GLOBAL, "file_size", 1); // large model: coordx, coordy, coordz apart
  file.Int(NC_GLOBAL, "maximum_name_length", static_cast<int>(nameLength - 1));
  file.Int(NC_GLOBAL, "int64_status", 0);

  file.Dimension("len_string", 33);
  file.Dimension("len_line", 81);
  file.Dimension("four", 4);
  const int name = file.Dimension("len_name", nameLength);
  const int time = file.Dimension("time_step", NC_UNLIMITED);
  const int dim = file.Dimension("num_dim", 3);
  const int nodes = file.Dimension("num_nodes", mesh.Points.size());
  const int elements = file.Dimension("num_elem", mesh.Tets.size());
  const int blocks = file.Dimension("num_el_blk", mesh.Tissues.size());
  const int sideSets = file.Dimension("num_side_sets", mesh.Surfaces.size());

  file.Variable("time_whole", NC_DOUBLE, { time });
  d.CoordX = file.Variable("coordx", NC_DOUBLE, { nodes });
  d.CoordY = file.Variable("coordy", NC_DOUBLE, { nodes });
  d.CoordZ = file.Variable("coordz", NC_DOUBLE, { nodes });
  d.CoordNames = file.Variable("coor_names", NC_CHAR, { dim, name });
  d.ElementMap = file.Variable("elem_num_map", NC_INT, { elements });

  d.BlockStatus = file.Variable("eb_status", NC_INT, { blocks });
  d.BlockIds = file.Variable("eb_prop1", NC_INT, { blocks });
  file.Text(d.BlockIds, "name", "ID");
  d.BlockNames = file.Variable("eb_names", NC_CHAR, { blocks, name });
  for (std::size_t b = 0; b < blockSizes.size(); ++b)
  {
    const std::string k = std::to_string(b + 1);
    const int count = file.Dimension("num_el_in_blk" + k, blockSizes[b]);
    const int corners = file.Dimension("num_nod_per_el" + k, 4);
    d.Connect.push_back(file.Variable("connect" + k, NC_INT, { count, corners }));
    // "TETRA" with 4 nodes per element is Exodus's linear tet (the type is its name and node
    // count); meshio 5.0 reads "TETRA" but fails on "TETRA4" (its type "tetra4" is unknown).
    file.Text(d.Connect.back(), "elem_type", "TETRA");
  }

  d.SideStatus = file.Variable("ss_status", NC_INT, { sideSets });
  d.SideIds = file.Variable("ss_prop1", NC_INT, { sideSets });
  file.Text(d.SideIds, "name", "ID");
  d.SideNames = file.Variable("ss_names", NC_CHAR, { sideSets, name });
  for (std::size_t s = 0; s < mesh.Surfaces.size(); ++s)
  {
    const std::string k = std::to_string(s + 1);
    const int count =
      file.Dimension("num_side_ss" + k, mesh.SurfaceStart[s + 1] - mesh.SurfaceStart[s]);
    d.SideElements.push_back(file.Variable("elem_ss" + k, NC_INT, { count }));
    d.SideSides.push_back(file.Variable("side_ss" + k, NC_INT, { count }));
  }
  file.EndDefinitions();
  return d;
}

// Why the mesh cannot go to Exodus (32-bit ids, no empty block or side set), or "".
std::string Unwritable(const TaggedMesh& mesh)
{
  if (mesh.Tets.empty())
    return "the mesh has no tetrahedra to write";
  if (mesh.Points.size() >= INT_MAX || mesh.Tets.size() >= INT_MAX)
    return "the mesh has too many points or tetrahedra for Exodus II's 32-bit ids";
  if (mesh.Surfaces.empty())
    return "the mesh has no boundary";
  for (std::size_t s = 0; s < mesh.Surfaces.size(); ++s)
  {
    if (mesh.SurfaceStart[s + 1] == mesh.SurfaceStart[s])
      return "the surface " + mesh.Surfaces[s].Name + " has no triangles";
  }
  return "";
}
} // namespace

std::vector<std::size_t> ExodusElementOrder(const TaggedMesh& mesh)
{
  std::vector<std::size_t> order(mesh.Tets.size());
  for (std::size_t t = 0; t < order.size(); ++t)
    order[t] = t;
  const auto block = [&](std::size_t t) {
    return std::lower_bound(mesh.Tissues.begin(), mesh.Tissues.end(), mesh.Labels[t]) -
      mesh.Tissues.begin();
  };
  std::stable_sort(order.begin(), order.end(),
    [&](std::size_t a, std::size_t b) { return block(a) < block(b); });
  return order;
}

Status WriteExodus(const TaggedMesh& mesh, const std::string& path)
{
  const std::string unwritable = Unwritable(mesh);
  if (!unwritable.empty())
    return Status::Error(unwritable);

  const std::vector<std::size_t> order = ExodusElementOrder(mesh);
  std::vector<int> element(mesh.Tets.size()); // tet -> its 1-based Exodus element
  for (std::size_t e = 0; e < order.size(); ++e)
    element[order[e]] = static_cast<int>(e + 1);
  const std::vector<std::size_t> blockSizes = TetsPerTissue(mesh);

  std::vector<std::string> blockNames, sideNames;
  std::size_t nameLength = NameLength;
  for (const std::int32_t label : mesh.Tissues)
    blockNames.push_back("tissue_" + std::to_string(LabelValue(mesh, label)));
  for (const TaggedSurface& surface : mesh.Surfaces)
    sideNames.push_back(surface.Name);
  for (const auto* names : { &blockNames, &sideNames })
    for (const std::string& n : *names)
      nameLength = std::max(nameLength, n.size() + 1);

  NetcdfFile file(path);
  const Definitions d = Define(file, mesh, blockSizes, nameLength);

  std::vector<double> x, y, z;
  for (const Eigen::Vector3d& p : mesh.Points)
  {
    x.push_back(p.x());
    y.push_back(p.y());
    z.push_back(p.z());
  }
  file.Put(d.CoordX, x);
  file.Put(d.CoordY, y);
  file.Put(d.CoordZ, z);
  file.Put(d.CoordNames, NameArray({ "x", "y", "z" }, nameLength));

  std::vector<int> map;
  for (const std::size_t t : order)
    map.push_back(static_cast<int>(t + 1));
  file.Put(d.ElementMap, map);

  file.Put(d.BlockStatus, std::vector<int>(mesh.Tissues.size(), 1));
  file.Put(d.BlockIds, BlockIds(mesh));
  file.Put(d.BlockNames, NameArray(blockNames, nameLength));
  std::size_t e = 0;
  for (std::size_t b = 0; b < blockSizes.size(); ++b)
  {
    std::vector<int> connect;
    for (std::size_t i = 0; i < blockSizes[b]; ++i, ++e)
    {
      for (const PointId p : mesh.Tets[order[e]])
        connect.push_back(static_cast<int>(p + 1));
    }
    file.Put(d.Connect[b], connect);
  }

  file.Put(d.SideStatus, std::vector<int>(mesh.Surfaces.size(), 1));
  std::vector<int> sideIds;
  for (const TaggedSurface& surface : mesh.Surfaces)
    sideIds.push_back(surface.Id);
  file.Put(d.SideIds, sideIds);
  file.Put(d.SideNames, NameArray(sideNames, nameLength));
  for (std::size_t s = 0; s < mesh.Surfaces.size(); ++s)
  {
    std::vector<int> elements, sides;
    for (std::size_t t = mesh.SurfaceStart[s]; t < mesh.SurfaceStart[s + 1]; ++t)
    {
      elements.push_back(element[static_cast<std::size_t>(mesh.Triangles[t].Tet)]);
      sides.push_back(ExodusSide(mesh.Triangles[t].Face));
    }
    file.Put(d.SideElements[s], elements);
    file.Put(d.SideSides[s], sides);
  }

  const std::string error = file.Close();
  return error.empty() ? Status::Ok() : Status::Error(error);
}
} // namespace cbc3d
