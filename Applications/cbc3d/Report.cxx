#include "Report.h"

#include "vtkCBC3DArrayNames.h"

#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkUnstructuredGrid.h>

#include <nlohmann/json.hpp>

#include <cstdio>
#include <sstream>

namespace
{
vtkDataArray* Field(vtkUnstructuredGrid* mesh, const char* name)
{
  return mesh->GetFieldData()->GetArray(name);
}

std::string Fixed(double value, int digits)
{
  char text[64];
  std::snprintf(text, sizeof(text), "%.*f", digits, value);
  return text;
}

nlohmann::json FiguresJson(const TissueFigures& figures)
{
  return { { "tetrahedra", figures.Tets }, { "min_dihedral_deg", figures.MinDihedral },
    { "max_dihedral_deg", figures.MaxDihedral }, { "inverted_tetrahedra", figures.Inverted } };
}
} // namespace

bool CollectQuality(vtkUnstructuredGrid* mesh, RunReport& report)
{
  namespace names = vtkCBC3DArrayNames;
  vtkDataArray* tets = Field(mesh, names::TetCount);
  vtkDataArray* minimum = Field(mesh, names::MinDihedralAngle);
  vtkDataArray* maximum = Field(mesh, names::MaxDihedralAngle);
  vtkDataArray* inverted = Field(mesh, names::InvertedTetCount);
  vtkDataArray* labels = Field(mesh, names::TissueLabel);
  vtkDataArray* tissueTets = Field(mesh, names::TissueTetCount);
  vtkDataArray* tissueMin = Field(mesh, names::TissueMinDihedralAngle);
  vtkDataArray* tissueMax = Field(mesh, names::TissueMaxDihedralAngle);
  vtkDataArray* tissueInverted = Field(mesh, names::TissueInvertedTetCount);
  if (!tets || !minimum || !maximum || !inverted || !labels || !tissueTets || !tissueMin ||
    !tissueMax || !tissueInverted)
  {
    return false;
  }
  report.Points = mesh->GetNumberOfPoints();
  report.Overall = { static_cast<long long>(tets->GetTuple1(0)), minimum->GetTuple1(0),
    maximum->GetTuple1(0), static_cast<long long>(inverted->GetTuple1(0)) };
  report.Tissues.clear();
  for (vtkIdType i = 0; i < labels->GetNumberOfTuples(); ++i)
  {
    report.Tissues[static_cast<int>(labels->GetTuple1(i))] = { static_cast<long long>(
                                                                 tissueTets->GetTuple1(i)),
      tissueMin->GetTuple1(i), tissueMax->GetTuple1(i),
      static_cast<long long>(tissueInverted->GetTuple1(i)) };
  }
  return true;
}

std::string FormatSummary(const RunReport& report)
{
  std::ostringstream out;
  out << report.Options.Input << " -> " << report.Options.Output << "\n";
  out << "  lattice size " << Fixed(report.BCCSizeUsed, 3) << " mm\n";
  out << "  tetrahedra " << report.Overall.Tets << ", points " << report.Points
      << ", inverted " << report.Overall.Inverted << "\n";
  out << "  tissue      tets  min dihedral  max dihedral\n";
  auto row = [&out](const std::string& name, const TissueFigures& f) {
    char line[160];
    std::snprintf(line, sizeof(line), "  %-6s %9lld  %11.2f°  %11.2f°\n", name.c_str(), f.Tets,
      f.MinDihedral, f.MaxDihedral);
    out << line;
  };
  for (const auto& [label, figures] : report.Tissues)
  {
    row(std::to_string(label), figures);
  }
  row("all", report.Overall);
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
  doc["parameters"] = { { "bcc_size_mm", report.BCCSizeUsed }, { "fidelity", o.Fidelity },
    { "pattern", o.Pattern }, { "iterations", o.Iterations },
    { "background", o.BackgroundLabels }, { "threads", o.Threads } };
  doc["tetrahedra"] = report.Overall.Tets;
  doc["points"] = report.Points;
  doc["min_dihedral_deg"] = report.Overall.MinDihedral;
  doc["max_dihedral_deg"] = report.Overall.MaxDihedral;
  doc["inverted_tetrahedra"] = report.Overall.Inverted;
  nlohmann::json seconds = nlohmann::json::object();
  for (const auto& [stage, value] : report.Seconds)
  {
    seconds[stage] = value;
  }
  doc["seconds"] = seconds;
  nlohmann::json tissues = nlohmann::json::object();
  for (const auto& [label, figures] : report.Tissues)
  {
    tissues[std::to_string(label)] = FiguresJson(figures);
  }
  doc["tissues"] = tissues;
  return doc.dump(2) + "\n";
}
