#include "MeshInvariants.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

void FailInvariant(const char* stage, const std::string& message)
{
  std::fprintf(stderr, "cbc3d fuzz: %s: %s\n", stage, message.c_str());
  std::abort();
}

void CheckMeshInvariants(const cbc3d::LabelImage& image, const cbc3d::TetMesh& mesh, const char* stage)
{
  const cbc3d::Status valid = cbc3d::ValidateTetMesh(mesh);
  if (!valid.IsOk())
  {
    FailInvariant(stage, valid.GetMessage());
  }
  for (const Eigen::Vector3d& point : mesh.Points)
  {
    if (!point.allFinite())
    {
      FailInvariant(stage, "a point is not finite");
    }
  }
  const std::vector<std::int32_t> tissues = image.TissueLabels();
  for (const std::int32_t label : mesh.Labels)
  {
    if (!std::binary_search(tissues.begin(), tissues.end(), label))
    {
      FailInvariant(stage, "tet label " + std::to_string(label) + " is not a tissue of the image");
    }
  }
}

void CheckSameTopology(const cbc3d::TetMesh& before, const cbc3d::TetMesh& after, const char* stage)
{
  if (before.Tets != after.Tets || before.Labels != after.Labels ||
    before.Points.size() != after.Points.size())
  {
    FailInvariant(stage, "the tets, their labels or the point count changed");
  }
}
