#ifndef cbc3d_Report_h
#define cbc3d_Report_h

#include "CommandLine.h"

#include <map>
#include <string>
#include <utility>
#include <vector>

class vtkUnstructuredGrid;

/// Dihedral figures of a set of tets, as vtkCBC3DMeshQuality reports them.
struct TissueFigures
{
  long long Tets = 0;
  double MinDihedral = 0.0;
  double MaxDihedral = 0.0;
  long long Inverted = 0;
};

/// What one run of cbc3d measured.
struct RunReport
{
  CommandLineOptions Options;
  double BCCSizeUsed = 0.0;
  long long Points = 0;
  TissueFigures Overall;
  std::map<int, TissueFigures> Tissues;
  std::vector<std::pair<std::string, double>> Seconds; // per stage, in order
};

/// Takes the figures from a mesh that went through vtkCBC3DMeshQuality (its field data), so
/// the report and the filter can never disagree. False if the field data is missing.
bool CollectQuality(vtkUnstructuredGrid* mesh, RunReport& report);

/// The summary printed on the terminal.
std::string FormatSummary(const RunReport& report);

/// The --report JSON document.
std::string FormatJson(const RunReport& report);

#endif
