#include "CommandLine.h"

#include "cbc3d/base/Parallel.h"
#include "cbc3d/export/MeshExport.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <initializer_list>
#include <map>
#include <sstream>

bool IsMeshExtension(const std::string& extension)
{
  return extension == ".vtu" || extension == ".vtk" || cbc3d::IsExportExtension(extension);
}

bool IsSurfaceExtension(const std::string& extension)
{
  return extension == ".vtp" || extension == ".vtk" || extension == ".stl" || extension == ".obj";
}

std::string UsageText()
{
  return R"(usage: cbc3d INPUT -o OUTPUT [-o OUTPUT]... [--msh-version 4.1|2.2] [--surfaces FILE]
             [--bcc-size MM] [--fidelity [L=]F]... [--boundary-distance MM]
             [--max-tets N] [--max-edge [L=]MM]... [--min-edge MM]
             [--pattern vertex|edge|face|none] [--targets centre|face]
             [--keep-volumes on|off]
             [--iterations N] [--background L]...
             [--threads N] [--report REPORT.json] [--quiet]

Mesh a 3-D label image into a conforming multi-tissue tetrahedral mesh (CBC3D).

  INPUT               label image: .nii .nii.gz .nrrd .nhdr .mha .mhd .vti
                      (NIfTI is placed in its world frame: sform, else qform, RAS mm)
  -o, --output FILE   mesh; repeat to write several formats from one run. The
                      extension picks the format: .vtu (VTK XML, binary), .vtk
                      (legacy 4.2, binary), .msh (Gmsh 4.1; 2.2 with --msh-version),
                      .inp (Abaqus), .mesh (Medit), .feb (FEBio 4.0), .xdmf
                      (FEniCSx/dolfinx, with a .h5 beside it), .exo (Exodus II).
                      The solver formats name each tissue tissue_<label>, each
                      boundary boundary_<label> and each interface
                      interface_<a>_<b> (Documentation/Exporting.md). Every file
                      is written whole or not at all
  --msh-version V     Gmsh .msh version: 4.1 (default) or 2.2 (older readers, SOFA)
  --surfaces FILE     also write the boundary and interface triangles: .vtp or .vtk
                      (cell arrays BoundaryLabels: the labels on both sides, and
                      SurfaceId), .stl or .obj (geometry only)
  --bcc-size MM       lattice cube edge in mm (default: 8 x the finest voxel spacing;
                      at most the image's extent along its widest axis)
  --fidelity [L=]F    voxel fidelity target in [0, 1] for refinement (default 0.95;
                      0 = no refinement); L=F sets it for tissue L alone (repeat for
                      several)
  --max-tets N        at most N tets: refinement spends them where they gain the
                      most fidelity, and the automatic lattice grows coarser where
                      it alone would hold more than a quarter of N
  --max-edge [L=]MM   no tet of a tissue keeps an edge longer than MM at the end of
                      refinement (default: no limit); L=MM for tissue L alone (repeat
                      for several). Tets near a tissue with a limit are refined too
  --min-edge MM       refinement makes no edge shorter than MM (default: the voxel
                      size, the cube root of the voxel volume)
  --boundary-distance MM
                      refinement adds surface vertices until every boundary voxel
                      would end within MM of one after deformation (the Hausdorff
                      measure), or a pass gains nothing by it; default 0 = 3/8 of
                      the lattice size; negative = none
  --pattern P         target-point pattern for deformation: vertex, edge, face, none
                      (default edge)
  --targets T         where deformation targets sit: face (default; on the label
                      boundary: tissues keep their volumes) or centre (the paper's
                      boundary voxel centres: about half a voxel of depth is lost)
  --keep-volumes on|off
                      deformation ends by moving the surfaces along their normals
                      until each tissue holds its voxels' volume (default on; off
                      leaves them inscribed in the boundary, short of the volume)
  --iterations N      deformation iterations (default 5; 0 = no deformation; at
                      most 1000: it stops once 5 in a row bring it no closer)
  --background L      a label that is not tissue; repeat for several (default 0)
  --threads N         threads, at most 1024 (default 0 = all cores); the mesh is
                      the same, byte for byte, for any number
  --report FILE       write the figures as JSON
  --quiet             print nothing but errors
  -h, --help          this text
  --version           the version

The BCC lattice alone: cbc3d IN -o OUT --fidelity 0 --iterations 0
)";
}

std::string FileExtension(const std::string& path)
{
  const std::size_t slash = path.find_last_of('/');
  std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  std::transform(name.begin(), name.end(), name.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  const std::size_t dot = name.find_last_of('.');
  if (dot == std::string::npos || dot == 0)
  {
    return "";
  }
  std::string extension = name.substr(dot);
  if (extension == ".gz")
  {
    const std::size_t inner = name.find_last_of('.', dot - 1);
    if (inner != std::string::npos && inner != 0)
    {
      extension = name.substr(inner);
    }
  }
  return extension;
}

namespace
{
// More deformation iterations than any image needs: the deformation stops once five in a row
// bring the surface no closer (13 on ball.vti, 16 on the brain).
constexpr int MaximumIterations = 1000;

bool ParseDouble(const std::string& text, double& value)
{
  char* end = nullptr;
  value = std::strtod(text.c_str(), &end);
  return !text.empty() && end && *end == '\0' && std::isfinite(value);
}

bool ParseInt(const std::string& text, int& value)
{
  char* end = nullptr;
  const long parsed = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || !end || *end != '\0' || parsed < -2147483647L - 1 || parsed > 2147483647L)
  {
    return false;
  }
  value = static_cast<int>(parsed);
  return true;
}

// A label: any 64-bit signed integer.
bool ParseLabel(const std::string& text, long long& value)
{
  char* end = nullptr;
  errno = 0;
  value = std::strtoll(text.c_str(), &end, 10);
  return !text.empty() && end && *end == '\0' && errno != ERANGE;
}

// Checks every -o and --surfaces extension and that no file is named twice.
bool CheckOutputs(const CommandLineOptions& options, std::string& error)
{
  std::vector<std::string> paths = options.Outputs;
  for (const std::string& output : options.Outputs)
  {
    const std::string extension = FileExtension(output);
    if (!IsMeshExtension(extension))
    {
      error = "unknown output extension '" + extension + "' for '" + output +
        "': use .vtu, .vtk, .msh, .inp, .mesh, .feb, .xdmf or .exo";
      return false;
    }
  }
  if (!options.SurfacesPath.empty())
  {
    const std::string extension = FileExtension(options.SurfacesPath);
    if (!IsSurfaceExtension(extension))
    {
      error = "unknown surfaces extension '" + extension + "' for '" + options.SurfacesPath +
        "': use .vtp, .vtk, .stl or .obj";
      return false;
    }
    paths.push_back(options.SurfacesPath);
  }
  paths.push_back(options.ReportPath);
  for (std::size_t i = 0; i < paths.size(); ++i)
  {
    for (std::size_t j = i + 1; j < paths.size(); ++j)
    {
      if (!paths[i].empty() && paths[i] == paths[j])
      {
        error = "the file '" + paths[i] + "' is given twice as an output";
        return false;
      }
    }
  }
  return true;
}

// The options as they are read: the first --background replaces the default 0.
struct Parsing
{
  CommandLineOptions& Options;
  std::vector<long long> Backgrounds;
};

// What an option's value does to the options; false, with `error`, where it is not allowed.
using SetValue = bool (*)(const std::string& text, Parsing& parsing, std::string& error);

// Every refusal of a value takes one form: "--name must be <allowed>, not '<text>'".
bool Refuse(const std::string& option, const std::string& allowed, const std::string& text, std::string& error)
{
  error = option + " must be " + allowed + ", not '" + text + "'";
  return false;
}

bool OneOf(const std::string& text, std::initializer_list<const char*> allowed)
{
  return std::any_of(allowed.begin(), allowed.end(), [&](const char* value) { return text == value; });
}

bool AddOutput(const std::string& text, Parsing& parsing, std::string&)
{
  parsing.Options.Outputs.push_back(text);
  return true;
}

// A value for every tissue ("F") or for one ("LABEL=F"), each checked by `allowed`.
bool SetPerTissue(const std::string& text, double& all, std::map<long long, double>& byTissue,
  bool (*allowed)(double))
{
  const std::size_t equals = text.find('=');
  double value = 0.0;
  if (equals == std::string::npos)
  {
    return ParseDouble(text, value) && allowed(value) && (all = value, true);
  }
  long long label = 0;
  if (!ParseLabel(text.substr(0, equals), label) || !ParseDouble(text.substr(equals + 1), value) || !allowed(value))
  {
    return false;
  }
  byTissue[label] = value;
  return true;
}

// The options that write files, and how the mesh is made.
const std::map<std::string, SetValue>& ValueOptions()
{
  static const std::map<std::string, SetValue> table = {
    { "-o", AddOutput },
    { "--output", AddOutput },
    { "--surfaces", [](const std::string& t, Parsing& p, std::string&) { p.Options.SurfacesPath = t; return true; } },
    { "--report", [](const std::string& t, Parsing& p, std::string&) { p.Options.ReportPath = t; return true; } },
    { "--msh-version", [](const std::string& t, Parsing& p, std::string& e) {
       p.Options.MshVersion = t;
       return OneOf(t, { "4.1", "2.2" }) || Refuse("--msh-version", "4.1 or 2.2", t, e); } },
    { "--bcc-size", [](const std::string& t, Parsing& p, std::string& e) {
       return (ParseDouble(t, p.Options.BCCSize) && p.Options.BCCSize > 0.0) ||
         Refuse("--bcc-size", "a positive number of millimetres", t, e); } },
    { "--fidelity", [](const std::string& t, Parsing& p, std::string& e) {
       return SetPerTissue(t, p.Options.Fidelity, p.Options.TissueFidelity,
                [](double f) { return f >= 0.0 && f <= 1.0; }) ||
         Refuse("--fidelity", "a number from 0 to 1, or LABEL=F", t, e); } },
    { "--max-edge", [](const std::string& t, Parsing& p, std::string& e) {
       return SetPerTissue(t, p.Options.MaxEdge, p.Options.TissueMaxEdge, [](double mm) { return mm > 0.0; }) ||
         Refuse("--max-edge", "a positive number of millimetres, or LABEL=MM", t, e); } },
    { "--max-tets", [](const std::string& t, Parsing& p, std::string& e) {
       return (ParseLabel(t, p.Options.MaxTets) && p.Options.MaxTets > 0) ||
         Refuse("--max-tets", "a positive whole number of tets", t, e); } },
    { "--min-edge", [](const std::string& t, Parsing& p, std::string& e) {
       return (ParseDouble(t, p.Options.MinEdge) && p.Options.MinEdge > 0.0) ||
         Refuse("--min-edge", "a positive number of millimetres", t, e); } },
    { "--boundary-distance", [](const std::string& t, Parsing& p, std::string& e) {
       return ParseDouble(t, p.Options.BoundaryDistance) ||
         Refuse("--boundary-distance", "a number of millimetres", t, e); } },
    { "--pattern", [](const std::string& t, Parsing& p, std::string& e) {
       p.Options.Pattern = t;
       return OneOf(t, { "vertex", "edge", "face", "none" }) || Refuse("--pattern", "vertex, edge, face or none", t, e); } },
    { "--targets", [](const std::string& t, Parsing& p, std::string& e) {
       p.Options.Targets = t;
       return OneOf(t, { "centre", "face" }) || Refuse("--targets", "centre or face", t, e); } },
    { "--keep-volumes", [](const std::string& t, Parsing& p, std::string& e) {
       p.Options.KeepVolumes = t == "on";
       return OneOf(t, { "on", "off" }) || Refuse("--keep-volumes", "on or off", t, e); } },
    { "--iterations", [](const std::string& t, Parsing& p, std::string& e) {
       const int most = MaximumIterations;
       return (ParseInt(t, p.Options.Iterations) && p.Options.Iterations >= 0 && p.Options.Iterations <= most) ||
         Refuse("--iterations", "a whole number from 0 to " + std::to_string(most) +
             " (deformation stops once the surface settles, long before)", t, e); } },
    { "--background", [](const std::string& t, Parsing& p, std::string& e) {
       long long label = 0;
       if (!ParseLabel(t, label))
         return Refuse("--background", "an integer label (64 bits)", t, e);
       p.Backgrounds.push_back(label);
       return true; } },
    { "--threads", [](const std::string& t, Parsing& p, std::string& e) {
       const int most = cbc3d::MaximumThreads;
       return (ParseInt(t, p.Options.Threads) && p.Options.Threads >= 0 && p.Options.Threads <= most) ||
         Refuse("--threads", "a whole number from 0 to " + std::to_string(most) + " (0 = all cores)", t, e); } },
  };
  return table;
}

// The input and the first output, once every option is read.
bool CheckPositional(const std::vector<std::string>& positional, CommandLineOptions& options, std::string& error)
{
  if (positional.size() != 1)
  {
    error = positional.empty() ? "no input image given (see cbc3d --help)"
                               : "more than one input given: '" + positional[1] + "'";
    return false;
  }
  options.Input = positional[0];
  if (options.Outputs.empty())
  {
    error = "no output file given: add -o OUTPUT.vtu";
    return false;
  }
  options.Output = options.Outputs.front();
  return CheckOutputs(options, error);
}
} // namespace

bool ParseCommandLine(int argc, char* argv[], CommandLineOptions& options, std::string& error)
{
  Parsing parsing{ options, {} };
  std::vector<std::string> positional;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    const auto valued = ValueOptions().find(arg);
    if (arg == "-h" || arg == "--help")
      options.ShowHelp = true;
    else if (arg == "--version")
      options.ShowVersion = true;
    else if (arg == "--quiet" || arg == "-q")
      options.Quiet = true;
    else if (valued != ValueOptions().end())
    {
      if (i + 1 >= argc)
      {
        error = "option " + arg + " needs a value";
        return false;
      }
      if (!valued->second(argv[++i], parsing, error))
        return false;
    }
    else if (arg.size() > 1 && arg[0] == '-')
    {
      error = "unknown option '" + arg + "' (see cbc3d --help)";
      return false;
    }
    else
      positional.push_back(arg);
  }
  if (!parsing.Backgrounds.empty())
  {
    options.BackgroundLabels = parsing.Backgrounds;
  }
  return options.ShowHelp || options.ShowVersion || CheckPositional(positional, options, error);
}
