#include "CommandLine.h"

#include "cbc3d/MeshExport.h"
#include "cbc3d/Parallel.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

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
} // namespace

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
             [--bcc-size MM] [--fidelity F] [--boundary-distance MM]
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
  --fidelity F        voxel fidelity target in [0, 1] for refinement (default 0.95;
                      0 = no refinement)
  --boundary-distance MM
                      refinement adds surface vertices until every boundary voxel
                      would end within MM of one after deformation (the Hausdorff
                      measure); default 0 = 3/8 of the lattice size; negative = none
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

bool ParseCommandLine(int argc, char* argv[], CommandLineOptions& options, std::string& error)
{
  bool backgroundGiven = false;
  std::vector<std::string> positional;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    auto value = [&](std::string& out) {
      if (i + 1 >= argc)
      {
        error = "option " + arg + " needs a value";
        return false;
      }
      out = argv[++i];
      return true;
    };
    std::string text;
    if (arg == "-h" || arg == "--help")
    {
      options.ShowHelp = true;
    }
    else if (arg == "--version")
    {
      options.ShowVersion = true;
    }
    else if (arg == "--quiet" || arg == "-q")
    {
      options.Quiet = true;
    }
    else if (arg == "-o" || arg == "--output")
    {
      if (!value(text))
        return false;
      options.Outputs.push_back(text);
    }
    else if (arg == "--surfaces")
    {
      if (!value(options.SurfacesPath))
        return false;
    }
    else if (arg == "--msh-version")
    {
      if (!value(options.MshVersion))
        return false;
      if (options.MshVersion != "4.1" && options.MshVersion != "2.2")
      {
        error = "--msh-version must be 4.1 or 2.2, not '" + options.MshVersion + "'";
        return false;
      }
    }
    else if (arg == "--report")
    {
      if (!value(options.ReportPath))
        return false;
    }
    else if (arg == "--bcc-size")
    {
      if (!value(text))
        return false;
      if (!ParseDouble(text, options.BCCSize) || !(options.BCCSize > 0.0))
      {
        error = "--bcc-size must be a positive number of millimetres, not '" + text + "'";
        return false;
      }
    }
    else if (arg == "--fidelity")
    {
      if (!value(text))
        return false;
      if (!ParseDouble(text, options.Fidelity) || options.Fidelity < 0.0 || options.Fidelity > 1.0)
      {
        error = "--fidelity must be a number from 0 to 1, not '" + text + "'";
        return false;
      }
    }
    else if (arg == "--boundary-distance")
    {
      if (!value(text))
        return false;
      if (!ParseDouble(text, options.BoundaryDistance))
      {
        error = "--boundary-distance must be a number of millimetres, not '" + text + "'";
        return false;
      }
    }
    else if (arg == "--pattern")
    {
      if (!value(options.Pattern))
        return false;
      if (options.Pattern != "vertex" && options.Pattern != "edge" && options.Pattern != "face" &&
        options.Pattern != "none")
      {
        error = "--pattern must be vertex, edge, face or none, not '" + options.Pattern + "'";
        return false;
      }
    }
    else if (arg == "--targets")
    {
      if (!value(options.Targets))
        return false;
      if (options.Targets != "centre" && options.Targets != "face")
      {
        error = "--targets must be centre or face, not '" + options.Targets + "'";
        return false;
      }
    }
    else if (arg == "--keep-volumes")
    {
      if (!value(text))
        return false;
      if (text != "on" && text != "off")
      {
        error = "--keep-volumes must be on or off, not '" + text + "'";
        return false;
      }
      options.KeepVolumes = text == "on";
    }
    else if (arg == "--iterations")
    {
      if (!value(text))
        return false;
      if (!ParseInt(text, options.Iterations) || options.Iterations < 0 || options.Iterations > MaximumIterations)
      {
        error = "--iterations must be a whole number from 0 to " + std::to_string(MaximumIterations) +
          " (deformation stops once the surface settles, long before), not '" + text + "'";
        return false;
      }
    }
    else if (arg == "--background")
    {
      if (!value(text))
        return false;
      long long label = 0;
      if (!ParseLabel(text, label))
      {
        error = "--background must be an integer label (64 bits), not '" + text + "'";
        return false;
      }
      if (!backgroundGiven)
      {
        options.BackgroundLabels.clear(); // the first --background replaces the default 0
        backgroundGiven = true;
      }
      options.BackgroundLabels.push_back(label);
    }
    else if (arg == "--threads")
    {
      if (!value(text))
        return false;
      if (!ParseInt(text, options.Threads) || options.Threads < 0 || options.Threads > cbc3d::MaximumThreads)
      {
        error = "--threads must be a whole number from 0 to " + std::to_string(cbc3d::MaximumThreads) +
          " (0 = all cores), not '" + text + "'";
        return false;
      }
    }
    else if (arg.size() > 1 && arg[0] == '-')
    {
      error = "unknown option '" + arg + "' (see cbc3d --help)";
      return false;
    }
    else
    {
      positional.push_back(arg);
    }
  }
  if (options.ShowHelp || options.ShowVersion)
  {
    return true;
  }
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
