#include "Report.h"

#include "vtkCBC3DArrayNames.h"

#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkStringArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkVariant.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <type_traits>
#include <utility>
#include <sstream>

namespace
{
vtkDataArray* Field(vtkUnstructuredGrid* mesh, const char* name)
{
  return mesh->GetFieldData()->GetArray(name);
}

// The first value of a string field array, "" when there is none.
std::string FieldText(vtkUnstructuredGrid* mesh, const char* name)
{
  auto* text = vtkStringArray::SafeDownCast(mesh->GetFieldData()->GetAbstractArray(name));
  return text && text->GetNumberOfValues() > 0 ? text->GetValue(0) : std::string();
}

std::string Fixed(double value, int digits)
{
  char text[64];
  std::snprintf(text, sizeof(text), "%.*f", digits, value);
  return text;
}

// JSON has no NaN: an unmeasured figure is null.
nlohmann::json Number(double value)
{
  return std::isnan(value) ? nlohmann::json(nullptr) : nlohmann::json(value);
}

void AddFigures(nlohmann::json& out, const TissueFigures& f)
{
  out["tetrahedra"] = f.Tets;
  out["min_dihedral_deg"] = Number(f.MinDihedral);
  out["max_dihedral_deg"] = Number(f.MaxDihedral);
  out["inverted_tetrahedra"] = f.Inverted;
  out["tetrahedra_under_10_deg"] = f.SmallAngle;
  out["tetrahedra_over_170_deg"] = f.LargeAngle;
  out["hausdorff_mm"] = Number(f.Hausdorff);
  out["mesh_to_image_mm"] = Number(f.MeshToImage);
  out["image_to_mesh_mm"] = Number(f.ImageToMesh);
  out["hausdorff_95_mm"] = Number(f.Hausdorff95);
  out["mean_distance_mm"] = Number(f.MeanDistance);
  out["volume_mm3"] = Number(f.Volume);
  out["image_volume_mm3"] = Number(f.ImageVolume);
  if (!std::isnan(f.F1))
  {
    out["fidelity_f1"] = f.F1;
    out["fidelity_f2"] = f.F2;
    out["components"] = f.Components;
    out["components_in_mesh"] = f.ComponentsInMesh;
  }
}

void AddTopology(nlohmann::json& out, const TissueFigures& f)
{
  out["face_components"] = f.FaceComponents;
  out["vertex_components"] = f.VertexComponents;
  out["hinged_parts"] = f.HingedParts;
  out["nonmanifold_edges"] = f.NonManifoldEdges;
  out["nonmanifold_vertices"] = f.NonManifoldVertices;
  out["surface_euler"] = f.SurfaceEuler;
  auto optional = [](const std::optional<long long>& value) {
    return value ? nlohmann::json(*value) : nlohmann::json(nullptr);
  };
  out["image_surface_euler"] = optional(f.ImageSurfaceEuler);
  out["image_surface_euler_pinches_joined"] = optional(f.ImagePinchesJoinedEuler);
  out["image_surface_euler_pinches_parted"] = optional(f.ImagePinchesPartedEuler);
}

// Reads the topology of the whole mesh (prefix "") or of tissue row i (prefix "Tissue") from
// the field data; an array that is missing leaves the figure as it was.
void ReadTopology(vtkUnstructuredGrid* mesh, const std::string& prefix, vtkIdType i, TissueFigures& f)
{
  namespace names = vtkCBC3DArrayNames;
  const std::pair<const char*, long long*> counts[] = { { names::FaceComponents, &f.FaceComponents },
    { names::VertexComponents, &f.VertexComponents }, { names::HingedParts, &f.HingedParts },
    { names::NonManifoldEdges, &f.NonManifoldEdges }, { names::NonManifoldVertices, &f.NonManifoldVertices },
    { names::SurfaceEuler, &f.SurfaceEuler } };
  for (const auto& [name, value] : counts)
  {
    if (vtkDataArray* array = Field(mesh, (prefix + name).c_str()))
    {
      *value = static_cast<long long>(array->GetTuple1(i));
    }
  }
  const std::pair<const char*, std::optional<long long>*> images[] = {
    { names::ImageSurfaceEuler, &f.ImageSurfaceEuler },
    { names::ImagePinchesJoinedEuler, &f.ImagePinchesJoinedEuler },
    { names::ImagePinchesPartedEuler, &f.ImagePinchesPartedEuler } };
  for (const auto& [name, value] : images)
  {
    if (vtkDataArray* image = Field(mesh, (prefix + name).c_str()))
    {
      *value = static_cast<long long>(image->GetTuple1(i));
    }
  }
}

std::string Plural(long long count, const char* one, const char* many)
{
  return std::to_string(count) + " " + (count == 1 ? one : many);
}

// The image's figure, and where its voxels pinch, the manifold readings round it.
std::string ImageEulerText(const TissueFigures& f)
{
  if (!f.ImageSurfaceEuler)
  {
    return "-";
  }
  std::string text = std::to_string(*f.ImageSurfaceEuler);
  if (f.ImagePinchesJoinedEuler && f.ImagePinchesPartedEuler &&
    (*f.ImagePinchesJoinedEuler != *f.ImageSurfaceEuler || *f.ImagePinchesPartedEuler != *f.ImageSurfaceEuler))
  {
    text += "; manifold " + std::to_string(*f.ImagePinchesJoinedEuler) + " joined, " +
      std::to_string(*f.ImagePinchesPartedEuler) + " parted";
  }
  return text;
}

std::string EulerText(const TissueFigures& f)
{
  return std::to_string(f.SurfaceEuler) + (f.ImageSurfaceEuler ? " (image " + ImageEulerText(f) + ")" : std::string());
}

// The per-tissue topology table and the one-line verdict on the whole mesh.
void FormatTopology(std::ostringstream& out, const RunReport& report)
{
  out << "  tissue  pieces (face / vertex)  hinged parts  non-manifold edges / vertices  Euler (image)\n";
  for (const auto& [label, f] : report.Tissues)
  {
    char line[240];
    std::snprintf(line, sizeof(line), "  %-6lld  %8lld / %-11lld  %12lld  %18lld / %-8lld  %lld (%s)\n", label,
      f.FaceComponents, f.VertexComponents, f.HingedParts, f.NonManifoldEdges, f.NonManifoldVertices,
      f.SurfaceEuler, ImageEulerText(f).c_str());
    out << line;
  }
  const TissueFigures& all = report.Overall;
  out << "  topology: " << Plural(all.FaceComponents, "piece", "pieces") << " (face) / "
      << all.VertexComponents << " (vertex), " << Plural(all.HingedParts, "hinged part", "hinged parts")
      << ", " << Plural(all.NonManifoldEdges, "non-manifold edge", "non-manifold edges") << ", "
      << Plural(all.NonManifoldVertices, "vertex", "vertices") << ", Euler "
      << EulerText(all) << ": " << (report.SolverReady ? "ready" : "NOT ready") << " for a solver\n";
}
} // namespace

bool CollectQuality(vtkUnstructuredGrid* mesh, RunReport& report)
{
  namespace names = vtkCBC3DArrayNames;
  // Reads value i of a field array; missing arrays leave the default (NaN or 0).
  auto read = [mesh](const char* name, vtkIdType i, auto& value) {
    if (vtkDataArray* array = Field(mesh, name))
    {
      value = static_cast<std::decay_t<decltype(value)>>(array->GetTuple1(i));
    }
  };
  vtkDataArray* labels = Field(mesh, names::TissueLabel);
  if (!labels || !Field(mesh, names::TetCount))
  {
    return false;
  }
  report.Points = mesh->GetNumberOfPoints();
  TissueFigures& all = report.Overall;
  read(names::TetCount, 0, all.Tets);
  read(names::InvertedTetCount, 0, all.Inverted);
  read(names::SmallAngleTetCount, 0, all.SmallAngle);
  read(names::LargeAngleTetCount, 0, all.LargeAngle);
  read(names::MinDihedralAngle, 0, all.MinDihedral);
  read(names::MaxDihedralAngle, 0, all.MaxDihedral);
  read(names::HausdorffDistance, 0, all.Hausdorff);
  read(names::HausdorffDistance95, 0, all.Hausdorff95);
  read(names::MeanSurfaceDistance, 0, all.MeanDistance);
  ReadTopology(mesh, "", 0, all);
  read(names::SolverReady, 0, report.SolverReady);
  report.Tissues.clear();
  for (vtkIdType i = 0; i < labels->GetNumberOfTuples(); ++i)
  {
    TissueFigures& tissue = report.Tissues[labels->GetVariantValue(i).ToLongLong()];
    ReadTopology(mesh, "Tissue", i, tissue);
    read(names::TissueTetCount, i, tissue.Tets);
    read(names::TissueInvertedTetCount, i, tissue.Inverted);
    read(names::TissueSmallAngleTetCount, i, tissue.SmallAngle);
    read(names::TissueLargeAngleTetCount, i, tissue.LargeAngle);
    read(names::TissueMinDihedralAngle, i, tissue.MinDihedral);
    read(names::TissueMaxDihedralAngle, i, tissue.MaxDihedral);
    read(names::TissueHausdorffDistance, i, tissue.Hausdorff);
    read(names::TissueMeshToImageDistance, i, tissue.MeshToImage);
    read(names::TissueImageToMeshDistance, i, tissue.ImageToMesh);
    read(names::TissueHausdorffDistance95, i, tissue.Hausdorff95);
    read(names::TissueMeanSurfaceDistance, i, tissue.MeanDistance);
    read(names::TissueVolume, i, tissue.Volume);
    read(names::TissueImageVolume, i, tissue.ImageVolume);
  }
  if (vtkDataArray* fidelityLabels = Field(mesh, names::FidelityLabel))
  {
    read(names::RefinementPasses, 0, report.RefinementPasses);
    read(names::RefinementBoundaryDistance, 0, report.RefinementBoundaryDistance);
    read(names::RefinementBoundaryGap, 0, report.RefinementBoundaryGap);
    read(names::RefinementRelabelledTets, 0, report.RefinementRelabelledTets);
    read(names::RefinementOverlongTets, 0, report.RefinementOverlongTets);
    report.RefinementStopReason = FieldText(mesh, names::RefinementStopReason);
    for (vtkIdType i = 0; i < fidelityLabels->GetNumberOfTuples(); ++i)
    {
      TissueFigures& tissue = report.Tissues[fidelityLabels->GetVariantValue(i).ToLongLong()];
      read(names::FidelityF1, i, tissue.F1);
      read(names::FidelityF2, i, tissue.F2);
      read(names::FidelityComponents, i, tissue.Components);
      read(names::FidelityComponentsInMesh, i, tissue.ComponentsInMesh);
    }
  }
  if (Field(mesh, names::DeformationIterations))
  {
    read(names::DeformationIterations, 0, report.DeformationIterations);
    read(names::DeformationSources, 0, report.DeformationSources);
    read(names::DeformationTargets, 0, report.DeformationTargets);
    report.DeformationStopReason = FieldText(mesh, names::DeformationStopReason);
  }
  // The mesh's one-sided distances are the largest over tissues, like its Hausdorff distance;
  // its volumes are the tissues' sums.
  all.MeshToImage = all.ImageToMesh = report.Tissues.empty() ? all.Hausdorff : 0.0;
  all.Volume = all.ImageVolume = 0.0;
  for (const auto& entry : report.Tissues)
  {
    const TissueFigures& t = entry.second;
    all.Volume += t.Volume;
    all.ImageVolume += t.ImageVolume;
    all.MeshToImage = std::isnan(t.MeshToImage) ? t.MeshToImage : std::max(all.MeshToImage, t.MeshToImage);
    all.ImageToMesh = std::isnan(t.ImageToMesh) ? t.ImageToMesh : std::max(all.ImageToMesh, t.ImageToMesh);
  }
  return true;
}

std::string FormatSummary(const RunReport& report)
{
  std::ostringstream out;
  out << report.Options.Input << " ->";
  for (const std::string& output : report.Options.Outputs)
  {
    out << " " << output;
  }
  if (!report.Options.SurfacesPath.empty())
  {
    out << " (surfaces " << report.Options.SurfacesPath << ")";
  }
  out << "\n";
  out << "  lattice size " << Fixed(report.BCCSizeUsed, 3) << " mm\n";
  out << "  tetrahedra " << report.Overall.Tets << ", points " << report.Points
      << ", inverted " << report.Overall.Inverted << "\n";
  out << "  tissue      tets  min dihedral  max dihedral  <10° >170°  Hausdorff mm (95%, mean)  volume / image\n";
  auto row = [&out](const std::string& name, const TissueFigures& f) {
    char line[200];
    std::snprintf(line, sizeof(line), "  %-6s %9lld  %11.2f°  %11.2f° %5lld %5lld  %8.2f (%.2f, %.2f)  %9.1f%%\n",
      name.c_str(), f.Tets, f.MinDihedral, f.MaxDihedral, f.SmallAngle, f.LargeAngle, f.Hausdorff,
      f.Hausdorff95, f.MeanDistance, 100.0 * f.Volume / f.ImageVolume);
    out << line;
  };
  for (const auto& [label, figures] : report.Tissues)
  {
    row(std::to_string(label), figures);
  }
  row("all", report.Overall);
  FormatTopology(out, report);
  if (report.RefinementPasses >= 0)
  {
    out << "  refinement: " << report.RefinementPasses << " passes, " << report.RefinementStopReason;
    if (report.RefinementBoundaryDistance > 0.0)
    {
      out << " (boundary distance " << Fixed(report.RefinementBoundaryDistance, 2)
          << " mm, predicted farthest voxel " << Fixed(report.RefinementBoundaryGap, 2) << " mm)";
    }
    if (report.RefinementOverlongTets > 0.0)
    {
      out << "; " << static_cast<long long>(report.RefinementOverlongTets)
          << " tissue tets keep an edge beyond their --max-edge (at --min-edge)";
    }
    out << "\n  tissue  F1      F2      components (kept / in image)\n";
    for (const auto& [label, f] : report.Tissues)
    {
      char line[160];
      std::snprintf(line, sizeof(line), "  %-6lld  %.4f  %.4f  %lld / %lld\n", label, f.F1, f.F2,
        f.ComponentsInMesh, f.Components);
      out << line;
    }
  }
  out << "  seconds:";
  for (const auto& [stage, seconds] : report.Seconds)
  {
    out << " " << stage << " " << Fixed(seconds, 3);
  }
  out << "\n";
  return out.str();
}

std::string FormatJson(const RunReport& report)
{
  const CommandLineOptions& o = report.Options;
  nlohmann::json doc;
  doc["input"] = o.Input;
  doc["output"] = o.Output;
  doc["outputs"] = o.Outputs;
  if (!o.SurfacesPath.empty())
  {
    doc["surfaces_file"] = o.SurfacesPath;
  }
  doc["parameters"] = { { "bcc_size_mm", report.BCCSizeUsed }, { "fidelity", o.Fidelity },
    { "boundary_distance_mm", o.BoundaryDistance },
    { "pattern", o.Pattern }, { "targets", o.Targets }, { "keep_volumes", o.KeepVolumes }, { "iterations", o.Iterations },
    { "background", o.BackgroundLabels }, { "threads", o.Threads }, { "max_edge_mm", o.MaxEdge },
    { "min_edge_mm", o.MinEdge }, { "max_tets", o.MaxTets } };
  for (const auto& [key, values] : { std::make_pair("tissue_fidelity", &o.TissueFidelity),
         std::make_pair("tissue_max_edge_mm", &o.TissueMaxEdge) })
  {
    nlohmann::json byLabel = nlohmann::json::object();
    for (const auto& [label, value] : *values)
      byLabel[std::to_string(label)] = value;
    doc["parameters"][key] = byLabel;
  }
  AddFigures(doc, report.Overall);
  doc["points"] = report.Points;
  nlohmann::json topology;
  AddTopology(topology, report.Overall);
  topology["solver_ready"] = report.SolverReady;
  doc["topology"] = topology;
  nlohmann::json seconds = nlohmann::json::object();
  for (const auto& [stage, value] : report.Seconds)
  {
    seconds[stage] = value;
  }
  doc["seconds"] = seconds;
  if (report.RefinementPasses >= 0)
  {
    doc["refinement"] = { { "passes", report.RefinementPasses },
      { "stop_reason", report.RefinementStopReason },
      { "boundary_distance_mm", report.RefinementBoundaryDistance },
      { "predicted_boundary_gap_mm", report.RefinementBoundaryGap },
      { "relabelled_tets", static_cast<long long>(report.RefinementRelabelledTets) },
      { "overlong_tets", static_cast<long long>(report.RefinementOverlongTets) } };
  }
  if (report.DeformationIterations >= 0)
  {
    doc["deformation"] = { { "iterations", report.DeformationIterations },
      { "stop_reason", report.DeformationStopReason }, { "sources", report.DeformationSources },
      { "targets", report.DeformationTargets } };
  }
  nlohmann::json tissues = nlohmann::json::object();
  for (const auto& [label, figures] : report.Tissues)
  {
    AddFigures(tissues[std::to_string(label)], figures);
    AddTopology(tissues[std::to_string(label)], figures);
  }
  doc["tissues"] = tissues;
  if (!report.Surfaces.empty())
  {
    nlohmann::json surfaces = nlohmann::json::object();
    for (const SurfaceFigures& surface : report.Surfaces)
    {
      surfaces[std::to_string(surface.Id)] = { { "name", surface.Name },
        { "labels", surface.Labels }, { "triangles", surface.Triangles } };
    }
    doc["surfaces"] = surfaces;
  }
  return doc.dump(2) + "\n";
}
