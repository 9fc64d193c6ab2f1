// A peer for the benchmark, never part of the library or plugin: meshes a label image with
// CGAL Mesh_3 (Labeled_mesh_domain_3, the CBC3D paper's CGAL settings by default), puts the mesh
// in the image's world frame, and measures it with vtkCBC3DMeshQuality, the ruler cbc3d uses.
//   CBC3DCGALMesh3 IMAGE.nii.gz OUT.vtu [--background L] [--deterministic]
//                  [--facet-size MM] [--facet-distance MM] [--cell-size MM] [--seed-components]
// --deterministic turns off the time limits of CGAL's perturber and exuder, whose default
// (the refinement's own time) makes the result depend on the machine's load. The three sizes
// (defaults 2, 2 and 2.5 mm, the paper's) let benchmark_meshing.py --curves trace CGAL's
// Hausdorff distance and time against its tet count; facet angle 30 and radius-edge ratio 1.5
// are shape criteria and stay the paper's. Prints a summary line, then one JSON line for
// benchmark_meshing.py (the mesh's figures, the sizes used, and each tissue's figures).
// --seed-components starts CGAL's refinement from a point on the surface of every connected
// component of the image (CGAL's initialize_triangulation_from_labeled_image) instead of
// make_mesh_3's random rays from the box's centre, which see nothing when the centre and the
// ends of every ray are background (a hollow shell round a cavity: no mesh at all).
#include "vtkCBC3DArrayNames.h"
#include "vtkCBC3DMeshQuality.h"
#include "vtkCBC3DNIfTIReader.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Image_3.h>
#include <CGAL/Labeled_mesh_domain_3.h>
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_criteria_3.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/Mesh_3/initialize_triangulation_from_labeled_image.h>
#include <CGAL/make_mesh_3.h>
#include <CGAL/refine_mesh_3.h>

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkImageData.h>
#include <vtkIntArray.h>
#include <vtkMatrix3x3.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkTetra.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Domain = CGAL::Labeled_mesh_domain_3<Kernel>;
using Triangulation = CGAL::Mesh_triangulation_3<Domain, CGAL::Default, CGAL::Sequential_tag>::type;
using Complex = CGAL::Mesh_complex_3_in_triangulation_3<Triangulation>;
using Criteria = CGAL::Mesh_criteria_3<Triangulation>;

namespace
{
const char* const Usage = "usage: CBC3DCGALMesh3 IMAGE.nii.gz OUT.vtu [--background L] [--deterministic] "
                          "[--facet-size MM] [--facet-distance MM] [--cell-size MM] [--seed-components]\n";

struct Options
{
  int Background = 0;
  bool Deterministic = false;
  bool SeedComponents = false;
  // The paper's CGAL size criteria, in mm.
  double FacetSize = 2.0;
  double FacetDistance = 2.0;
  double CellSize = 2.5;
};

// A size criterion: a finite number of mm above 0 (CGAL reads 0 as "no bound", which
// would silently mesh something else than asked).
bool ParseSize(const char* text, double& size)
{
  char* end = nullptr;
  const double value = std::strtod(text, &end);
  if (end == text || *end != '\0' || !std::isfinite(value) || value <= 0)
    return false;
  size = value;
  return true;
}

bool ParseLabel(const char* text, int& label)
{
  char* end = nullptr;
  const long value = std::strtol(text, &end, 10);
  if (end == text || *end != '\0' || value < std::numeric_limits<int>::min() ||
    value > std::numeric_limits<int>::max())
    return false;
  label = static_cast<int>(value);
  return true;
}

// Reads the options after IMAGE and OUT; on a bad one prints one line and returns false.
bool ParseOptions(int argc, char* argv[], Options& options)
{
  for (int i = 3; i < argc; ++i)
  {
    const char* name = argv[i];
    if (std::strcmp(name, "--deterministic") == 0)
    {
      options.Deterministic = true;
      continue;
    }
    if (std::strcmp(name, "--seed-components") == 0)
    {
      options.SeedComponents = true;
      continue;
    }
    double* size = std::strcmp(name, "--facet-size") == 0 ? &options.FacetSize
      : std::strcmp(name, "--facet-distance") == 0        ? &options.FacetDistance
      : std::strcmp(name, "--cell-size") == 0             ? &options.CellSize
                                                          : nullptr;
    const bool background = std::strcmp(name, "--background") == 0;
    if (!size && !background)
    {
      std::fprintf(stderr, "CBC3DCGALMesh3: unknown option %s\n", name);
      return false;
    }
    if (i + 1 >= argc)
    {
      std::fprintf(stderr, "CBC3DCGALMesh3: %s needs a value\n", name);
      return false;
    }
    const char* text = argv[++i];
    if (background ? !ParseLabel(text, options.Background) : !ParseSize(text, *size))
    {
      std::fprintf(stderr, "CBC3DCGALMesh3: %s %s: expected %s\n", name, text,
        background ? "an integer label" : "a size in mm above 0");
      return false;
    }
  }
  return true;
}
} // namespace

int main(int argc, char* argv[])
{
  if (argc < 3)
  {
    std::fputs(Usage, stderr);
    return 2;
  }
  Options options;
  if (!ParseOptions(argc, argv, options))
    return 2;
  const int background = options.Background;
  const bool deterministic = options.Deterministic;
  vtkNew<vtkCBC3DNIfTIReader> reader;
  reader->SetFileName(argv[1]);
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  vtkDataArray* labels = image->GetPointData()->GetScalars();
  if (!labels)
  {
    std::fprintf(stderr, "cannot read %s\n", argv[1]);
    return 1;
  }
  // CGAL's domain calls 0 outside: background becomes 0, and a tissue labelled 0 (possible
  // with another background) gets a free code that is mapped back afterwards.
  int dims[3];
  image->GetDimensions(dims);
  const double* spacing = image->GetSpacing();
  std::map<int, int> codeOfLabel, labelOfCode;
  _image* raw = _createImage(dims[0], dims[1], dims[2], 1, spacing[0], spacing[1], spacing[2], 2,
    WK_FIXED, SGN_UNSIGNED);
  auto* data = static_cast<std::uint16_t*>(raw->data);
  for (vtkIdType v = 0; v < labels->GetNumberOfTuples(); ++v)
  {
    const int label = static_cast<int>(labels->GetTuple1(v));
    if (label == background)
    {
      data[v] = 0;
      continue;
    }
    auto found = codeOfLabel.find(label);
    if (found == codeOfLabel.end())
    {
      const int code = static_cast<int>(codeOfLabel.size()) + 1;
      found = codeOfLabel.emplace(label, code).first;
      labelOfCode[code] = label;
    }
    data[v] = static_cast<std::uint16_t>(found->second);
  }
  CGAL::Image_3 cgalImage(raw);
  Domain domain = Domain::create_labeled_image_mesh_domain(cgalImage);
  namespace p = CGAL::parameters;
  Criteria criteria(p::facet_angle = 30, p::facet_size = options.FacetSize, p::facet_distance = options.FacetDistance,
    p::cell_radius_edge_ratio = 1.5, p::cell_size = options.CellSize);
  const auto start = std::chrono::steady_clock::now();
  Complex complex;
  if (options.SeedComponents)
  {
    // CGAL reports its search on std::cout, where this program's JSON line goes: silenced.
    std::ostringstream chatter;
    std::streambuf* const out = std::cout.rdbuf(chatter.rdbuf());
    ::initialize_triangulation_from_labeled_image(complex, domain, cgalImage, criteria, std::uint16_t());
    std::cout.rdbuf(out);
    if (deterministic)
      CGAL::refine_mesh_3(complex, domain, criteria, p::perturb(p::time_limit = 0), p::exude(p::time_limit = 0));
    else
      CGAL::refine_mesh_3(complex, domain, criteria);
  }
  else
  {
    complex = deterministic
      ? CGAL::make_mesh_3<Complex>(domain, criteria, p::perturb(p::time_limit = 0), p::exude(p::time_limit = 0))
      : CGAL::make_mesh_3<Complex>(domain, criteria);
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  // Into the image's world frame: CGAL's point is spacing .* index, as vtkImageData's before
  // its origin and direction.
  const double* origin = image->GetOrigin();
  vtkMatrix3x3* direction = image->GetDirectionMatrix();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  std::map<Triangulation::Vertex_handle, vtkIdType> ids;
  vtkNew<vtkUnstructuredGrid> mesh;
  vtkNew<vtkIntArray> tetLabels;
  tetLabels->SetName(vtkCBC3DArrayNames::Label);
  for (auto cell = complex.cells_in_complex_begin(); cell != complex.cells_in_complex_end(); ++cell)
  {
    vtkIdType tet[4];
    double x[4][3];
    for (int v = 0; v < 4; ++v)
    {
      const auto vertex = cell->vertex(v);
      auto found = ids.find(vertex);
      if (found == ids.end())
      {
        const auto q = vertex->point().point();
        const double local[3] = { q.x(), q.y(), q.z() };
        double world[3];
        for (int r = 0; r < 3; ++r)
          world[r] = origin[r] + direction->GetElement(r, 0) * local[0] + direction->GetElement(r, 1) * local[1] +
            direction->GetElement(r, 2) * local[2];
        found = ids.emplace(vertex, points->InsertNextPoint(world)).first;
      }
      tet[v] = found->second;
      points->GetPoint(tet[v], x[v]);
    }
    if (vtkTetra::ComputeVolume(x[0], x[1], x[2], x[3]) < 0)
      std::swap(tet[2], tet[3]);
    mesh->InsertNextCell(VTK_TETRA, 4, tet);
    tetLabels->InsertNextValue(labelOfCode[static_cast<int>(complex.subdomain_index(cell))]);
  }
  mesh->SetPoints(points);
  mesh->GetCellData()->AddArray(tetLabels);

  vtkNew<vtkCBC3DMeshQuality> quality;
  quality->SetInputData(mesh);
  quality->SetImageData(image);
  quality->SetBackgroundLabel(background);
  quality->Update();
  vtkFieldData* f = quality->GetOutput()->GetFieldData();
  std::printf("CGAL Mesh_3 (%s; facet size %g, facet distance %g, cell size %g mm): %lld tets, %lld points, "
              "dihedral %.2f / %.2f deg, Hausdorff %.2f mm (95%% %.2f, mean %.2f), %.1f s\n",
    deterministic ? "no time limits" : "default time limits", options.FacetSize, options.FacetDistance,
    options.CellSize,
    static_cast<long long>(mesh->GetNumberOfCells()), static_cast<long long>(mesh->GetNumberOfPoints()),
    f->GetArray("MinDihedralAngle")->GetTuple1(0), f->GetArray("MaxDihedralAngle")->GetTuple1(0),
    f->GetArray("HausdorffDistance")->GetTuple1(0), f->GetArray("HausdorffDistance95")->GetTuple1(0),
    f->GetArray("MeanSurfaceDistance")->GetTuple1(0), seconds);
  // One JSON line for the benchmark script, with the keys of cbc3d's --report, the mesh's
  // figures and each tissue's Hausdorff distances, volumes and topology.
  namespace names = vtkCBC3DArrayNames;
  auto value = [f](const char* name, vtkIdType i) { return f->GetArray(name)->GetTuple1(i); };
  // Topology, with cbc3d's report keys: the whole mesh's (prefix "") or tissue row i's ("Tissue").
  auto topology = [&value](const std::string& prefix, vtkIdType i) {
    char keys[384];
    std::snprintf(keys, sizeof(keys),
      "\"face_components\": %lld, \"vertex_components\": %lld, \"hinged_parts\": %lld, "
      "\"nonmanifold_edges\": %lld, \"nonmanifold_vertices\": %lld, \"surface_euler\": %lld, "
      "\"image_surface_euler\": %lld",
      static_cast<long long>(value((prefix + names::FaceComponents).c_str(), i)),
      static_cast<long long>(value((prefix + names::VertexComponents).c_str(), i)),
      static_cast<long long>(value((prefix + names::HingedParts).c_str(), i)),
      static_cast<long long>(value((prefix + names::NonManifoldEdges).c_str(), i)),
      static_cast<long long>(value((prefix + names::NonManifoldVertices).c_str(), i)),
      static_cast<long long>(value((prefix + names::SurfaceEuler).c_str(), i)),
      static_cast<long long>(value((prefix + names::ImageSurfaceEuler).c_str(), i)));
    return std::string(keys);
  };
  char text[2048];
  std::snprintf(text, sizeof(text),
    "{\"tetrahedra\": %lld, \"points\": %lld, \"min_dihedral_deg\": %.6f, \"max_dihedral_deg\": %.6f, "
    "\"hausdorff_mm\": %.6f, \"hausdorff_95_mm\": %.6f, \"mean_distance_mm\": %.6f, \"seconds\": %.3f, "
    "\"criteria\": {\"facet_size_mm\": %g, \"facet_distance_mm\": %g, \"cell_size_mm\": %g}, "
    "\"topology\": {%s, \"solver_ready\": %s}, \"tissues\": {",
    static_cast<long long>(mesh->GetNumberOfCells()), static_cast<long long>(mesh->GetNumberOfPoints()),
    value(names::MinDihedralAngle, 0), value(names::MaxDihedralAngle, 0), value(names::HausdorffDistance, 0),
    value(names::HausdorffDistance95, 0), value(names::MeanSurfaceDistance, 0), seconds, options.FacetSize,
    options.FacetDistance, options.CellSize, topology("", 0).c_str(), value(names::SolverReady, 0) != 0 ? "true" : "false");
  std::string json = text;
  const vtkIdType tissues = f->GetArray(names::TissueLabel) ? f->GetArray(names::TissueLabel)->GetNumberOfTuples() : 0;
  for (vtkIdType i = 0; i < tissues; ++i)
  {
    std::snprintf(text, sizeof(text),
      "%s\"%d\": {\"tetrahedra\": %lld, \"hausdorff_mm\": %.6f, \"hausdorff_95_mm\": %.6f, \"mean_distance_mm\": %.6f, "
      "\"volume_mm3\": %.6f, \"image_volume_mm3\": %.6f, %s}",
      i ? ", " : "", static_cast<int>(value(names::TissueLabel, i)),
      static_cast<long long>(value(names::TissueTetCount, i)), value(names::TissueHausdorffDistance, i),
      value(names::TissueHausdorffDistance95, i), value(names::TissueMeanSurfaceDistance, i),
      value(names::TissueVolume, i), value(names::TissueImageVolume, i), topology("Tissue", i).c_str());
    json += text;
  }
  std::printf("%s}}\n", json.c_str());
  vtkNew<vtkXMLUnstructuredGridWriter> writer;
  writer->SetInputConnection(quality->GetOutputPort());
  writer->SetFileName(argv[2]);
  writer->SetDataModeToBinary();
  return writer->Write() ? 0 : 1;
}
