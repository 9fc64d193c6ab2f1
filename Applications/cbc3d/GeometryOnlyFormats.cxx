#include "GeometryOnlyFormats.h"

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkIdList.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <sstream>

namespace
{
template <typename T>
void Append(std::string& bytes, T value)
{
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T)); // STL is little-endian, as every machine we build on
  bytes.append(raw, sizeof(T));
}

std::array<double, 3> UnitNormal(const double a[3], const double b[3], const double c[3])
{
  const double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
  const double v[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
  std::array<double, 3> n = { u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
    u[0] * v[1] - u[1] * v[0] };
  const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  for (double& x : n)
    x = length > 0.0 ? x / length : 0.0;
  return n;
}
} // namespace

std::string StlBytes(vtkPolyData* surfaces)
{
  std::string bytes = "cbc3d tissue surfaces";
  bytes.resize(80, ' ');
  vtkCellArray* triangles = surfaces->GetPolys();
  Append<std::uint32_t>(bytes, static_cast<std::uint32_t>(triangles->GetNumberOfCells()));
  auto cells = vtk::TakeSmartPointer(triangles->NewIterator());
  for (cells->GoToFirstCell(); !cells->IsDoneWithTraversal(); cells->GoToNextCell())
  {
    vtkIdList* ids = cells->GetCurrentCell();
    double corners[3][3];
    for (int v = 0; v < 3; ++v)
      surfaces->GetPoint(ids->GetId(v), corners[v]);
    for (const double x : UnitNormal(corners[0], corners[1], corners[2]))
      Append<float>(bytes, static_cast<float>(x));
    for (const auto& corner : corners)
      for (const double x : corner)
        Append<float>(bytes, static_cast<float>(x));
    Append<std::uint16_t>(bytes, 0);
  }
  return bytes;
}

std::string ObjText(vtkPolyData* surfaces)
{
  std::ostringstream text;
  text.precision(17);
  text << "# cbc3d tissue surfaces\n";
  for (vtkIdType p = 0; p < surfaces->GetNumberOfPoints(); ++p)
  {
    double x[3];
    surfaces->GetPoint(p, x);
    text << "v " << x[0] << " " << x[1] << " " << x[2] << "\n";
  }
  auto cells = vtk::TakeSmartPointer(surfaces->GetPolys()->NewIterator());
  for (cells->GoToFirstCell(); !cells->IsDoneWithTraversal(); cells->GoToNextCell())
  {
    vtkIdList* ids = cells->GetCurrentCell();
    text << "f " << ids->GetId(0) + 1 << " " << ids->GetId(1) + 1 << " " << ids->GetId(2) + 1 << "\n";
  }
  return text.str();
}
