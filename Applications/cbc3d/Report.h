#ifndef cbc3d_Report_h
#define cbc3d_Report_h

#include "CommandLine.h"

#include <array>
#include <limits>
#include <map>
#include <optional>
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
  long long SmallAngle = 0; // tets with an angle under 10 degrees
  long long LargeAngle = 0; // tets with an angle over 170 degrees
  // Distances to the image boundary in mm (NaN: not measured, or a tissue on one side only).
  double Hausdorff = std::numeric_limits<double>::quiet_NaN();
  double MeshToImage = std::numeric_limits<double>::quiet_NaN();
  double ImageToMesh = std::numeric_limits<double>::quiet_NaN();
  double Hausdorff95 = std::numeric_limits<double>::quiet_NaN();
  double MeanDistance = std::numeric_limits<double>::quiet_NaN();
  // Volumes in mm^3: of the tissue's tets, and of its voxels (NaN without the image).
  double Volume = std::numeric_limits<double>::quiet_NaN();
  double ImageVolume = std::numeric_limits<double>::quiet_NaN();
  // Voxel fidelity after refinement (NaN without refinement) and tissue components.
  double F1 = std::numeric_limits<double>::quiet_NaN();
  double F2 = std::numeric_limits<double>::quiet_NaN();
  long long Components = -1;
  long long ComponentsInMesh = -1;
  // Topology (vtkCBC3DMeshQuality): components through faces and through vertices, hinged
  // parts, non-manifold surface edges and vertices (the mesh's: its body's plus its tissues'),
  // the surface's Euler characteristic and, with the image, its voxels' (absent without).
  long long FaceComponents = 0;
  long long VertexComponents = 0;
  long long HingedParts = 0;
  long long NonManifoldEdges = 0;
  long long NonManifoldVertices = 0;
  long long SurfaceEuler = 0;
  std::optional<long long> ImageSurfaceEuler;
  // A manifold surface round the same voxels with every pinch joined, and every one parted
  // (cbc3d::ImageTopology): the voxel-face figure is their mean.
  std::optional<long long> ImagePinchesJoinedEuler;
  std::optional<long long> ImagePinchesPartedEuler;
};

/// What one run of cbc3d measured.
/// A boundary or interface as the solver formats tag it (cbc3d::TaggedSurface).
struct SurfaceFigures
{
  int Id = 0;
  std::string Name;
  std::array<long long, 2> Labels = { 0, 0 }; // behind the triangles, in front (the outside label)
  long long Triangles = 0;
};

struct RunReport
{
  CommandLineOptions Options;
  double BCCSizeUsed = 0.0;
  long long Points = 0;
  TissueFigures Overall;
  bool SolverReady = false; // no hinged part, no non-manifold edge or vertex anywhere
  std::map<long long, TissueFigures> Tissues; // by label value
  std::vector<std::pair<std::string, double>> Seconds; // per stage, in order
  int RefinementPasses = -1;                           // -1: no refinement
  std::string RefinementStopReason;
  double RefinementBoundaryDistance = 0.0; // the bound used (mm); 0 when none
  double RefinementRelabelledTets = 0.0;  // tets relabelled for sound labels
  double RefinementOverlongTets = 0.0;    // tissue tets with an edge beyond --max-edge
  double RefinementBoundaryGap = 0.0;      // farthest boundary voxel from the predicted surface
  int DeformationIterations = -1;          // -1: no deformation
  std::string DeformationStopReason;
  long long DeformationSources = 0;        // surface and interface vertices
  long long DeformationTargets = 0;        // boundary voxels kept by the pattern
  std::vector<SurfaceFigures> Surfaces;    // when a solver format or --surfaces was written
};

/// Takes the figures from a mesh that went through vtkCBC3DMeshQuality (its field data), so
/// the report and the filter can never disagree. False if the field data is missing.
bool CollectQuality(vtkUnstructuredGrid* mesh, RunReport& report);

/// The summary printed on the terminal.
std::string FormatSummary(const RunReport& report);

/// The --report JSON document.
std::string FormatJson(const RunReport& report);

#endif
