#ifndef cbc3d_CommandLine_h
#define cbc3d_CommandLine_h

#include <map>
#include <string>
#include <vector>

/// The options of the cbc3d command (a fixed interface: scripts depend on it).
struct CommandLineOptions
{
  std::string Input;
  std::string Output;                // the first -o (the report's "output")
  std::vector<std::string> Outputs;  // every -o, in order; the extension picks the format
  std::string MshVersion = "4.1";    // Gmsh .msh: 4.1 or 2.2
  std::string SurfacesPath;          // --surfaces: the boundary and interface triangles
  double BCCSize = 0.0;    // mm; 0 = 8 x the finest voxel spacing
  double Fidelity = 0.95;  // 0 = no refinement
  std::map<long long, double> TissueFidelity; // --fidelity LABEL=F
  double MaxEdge = 0.0;    // mm; 0 = no limit
  std::map<long long, double> TissueMaxEdge;  // --max-edge LABEL=MM
  double MinEdge = 0.0;    // mm; 0 = the voxel size
  long long MaxTets = 0;   // a tet budget; 0 = none
  double BoundaryDistance = 0.0; // mm; 0 = 3/8 of the lattice size, negative = none
  std::string Pattern = "edge";
  std::string Targets = "face";   // where deformation targets sit: centre or face
  bool KeepVolumes = true;        // deformation ends with each tissue at its voxels' volume
  int Iterations = 5;      // 0 = no deformation
  std::vector<long long> BackgroundLabels = { 0 };
  int Threads = 0;         // 0 = all cores
  std::string ReportPath;
  bool Quiet = false;
  bool ShowHelp = false;
  bool ShowVersion = false;
};

/// Parses argv; false with a one-line message on any unknown option or bad value.
bool ParseCommandLine(int argc, char* argv[], CommandLineOptions& options, std::string& error);

/// The --help text.
std::string UsageText();

/// Whether an -o extension names a format cbc3d writes.
bool IsMeshExtension(const std::string& extension);

/// Whether a --surfaces extension names a format cbc3d writes: .vtp, .vtk, .stl, .obj.
bool IsSurfaceExtension(const std::string& extension);

/// The lower-cased file-name extension with its dot, e.g. ".nii.gz", ".vtu"; "" if none.
std::string FileExtension(const std::string& path);

#endif
