// cbc3d: the command-line mesher. Reads a label image, runs the CBC3D stages, measures the
// mesh with vtkCBC3DMeshQuality, and writes the mesh (and a JSON report) all or nothing.
#include "CommandLine.h"
#include "ErrorCapture.h"
#include "ExportFileWriter.h"
#include "HugePages.h"
#include "ImageFileReader.h"
#include "MeshFileWriter.h"
#include "Report.h"
#include "StopSignals.h"

#include "vtkCBC3DArrayNames.h"
#include "vtkCBC3DBCCLattice.h"
#include "vtkCBC3DConvert.h"
#include "vtkCBC3DDeformation.h"
#include "vtkCBC3DMeshQuality.h"
#include "vtkCBC3DRefinement.h"

#include "cbc3d/base/Parallel.h"
#include "cbc3d/export/MeshExport.h"

#include <vtkAlgorithm.h>
#include <vtkCallbackCommand.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>
#include <chrono>
#include <initializer_list>
#include <cstdio>
#include <iostream>
#include <malloc.h>
#include <new>
#include <stdexcept>
#include <unistd.h>

namespace
{
// Every error ends here: the run's files go (an output appears only when the whole run did).
int Fail(const std::string& message, int code = 1)
{
  RemoveRunFiles();
  std::cerr << "cbc3d: error: " << message << std::endl;
  return code;
}

// Shows "stage  NN%" on a terminal; silent when stderr is not one.
struct ProgressLine
{
  std::string Stage;
  int LastPercent = -1;

  static void Callback(vtkObject* caller, unsigned long, void* clientData, void*)
  {
    auto* self = static_cast<ProgressLine*>(clientData);
    const int percent = static_cast<int>(100.0 * static_cast<vtkAlgorithm*>(caller)->GetProgress());
    if (percent != self->LastPercent)
    {
      self->LastPercent = percent;
      std::fprintf(stderr, "\r  %-10s %3d%%", self->Stage.c_str(), percent);
      std::fflush(stderr);
    }
  }
};

void SetBackground(vtkCBC3DAlgorithm* filter, const CommandLineOptions& options)
{
  filter->RemoveAllBackgroundLabels();
  for (const long long label : options.BackgroundLabels)
  {
    filter->AddBackgroundLabel(label);
  }
}

int PatternValue(const std::string& pattern)
{
  return pattern == "vertex" ? vtkCBC3DDeformation::VERTEX
    : pattern == "face"      ? vtkCBC3DDeformation::FACE
    : pattern == "none"      ? vtkCBC3DDeformation::NONE
                             : vtkCBC3DDeformation::EDGE;
}

class Stopwatch
{
public:
  double Seconds() const
  {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - this->Start).count();
  }

private:
  std::chrono::steady_clock::time_point Start = std::chrono::steady_clock::now();
};

// Runs one stage: progress on a terminal, errors caught as one line, time recorded.
bool RunStage(vtkAlgorithm* stage, const std::string& name, bool showProgress, RunReport& report,
  std::string& error)
{
  vtkNew<ErrorCapture> capture;
  capture->Observe(stage);
  ProgressLine line{ name };
  vtkNew<vtkCallbackCommand> progress;
  progress->SetCallback(&ProgressLine::Callback);
  progress->SetClientData(&line);
  if (showProgress)
  {
    stage->AddObserver(vtkCommand::ProgressEvent, progress);
  }
  Stopwatch clock;
  stage->Update();
  report.Seconds.emplace_back(name, clock.Seconds());
  if (showProgress)
  {
    std::fprintf(stderr, "\r%40s\r", "");
    stage->RemoveObserver(progress);
  }
  if (!capture->Error.empty())
  {
    error = capture->Error;
    return false;
  }
  return true;
}

bool WriteExport(
  const cbc3d::TaggedMesh& tagged, const std::string& path, bool gmsh22, std::string& error)
{
  const cbc3d::Status status = cbc3d::WriteExportFile(tagged, path, gmsh22);
  error = status.GetMessage();
  return status.IsOk();
}

// Writes every -o file (the extension picks the format) and the --surfaces file; the solver
// formats and the surfaces share one tagged mesh, the outside being the first background label.
// The surfaces' ids, names and sizes, for the report: the key to Medit's refs and XDMF's tags.
void ReportSurfaces(const cbc3d::TaggedMesh& tagged, RunReport& report)
{
  for (std::size_t s = 0; s < tagged.Surfaces.size(); ++s)
  {
    const cbc3d::TaggedSurface& surface = tagged.Surfaces[s];
    report.Surfaces.push_back({ surface.Id, surface.Name,
      { cbc3d::LabelValue(tagged, surface.Sides[0]), cbc3d::LabelValue(tagged, surface.Sides[1]) },
      static_cast<long long>(tagged.SurfaceStart[s + 1] - tagged.SurfaceStart[s]) });
  }
}

bool WriteOutputs(
  vtkUnstructuredGrid* mesh, const CommandLineOptions& options, RunReport& report, std::string& error)
{
  cbc3d::TaggedMesh tagged;
  bool taggedReady = false;
  auto tag = [&]() {
    if (!taggedReady && vtkCBC3DConvert::ToTaggedMesh(mesh, options.BackgroundLabels.front(), tagged, error))
    {
      taggedReady = true;
      ReportSurfaces(tagged, report);
    }
    return taggedReady;
  };
  for (const std::string& output : options.Outputs)
  {
    const std::string extension = FileExtension(output);
    const bool ok = extension == ".vtu" || extension == ".vtk"
      ? WriteMeshFile(mesh, output, options.Threads, error)
      : tag() && WriteExport(tagged, output, options.MshVersion == "2.2", error);
    if (!ok)
    {
      return false;
    }
  }
  return options.SurfacesPath.empty() || (tag() && WriteSurfaceFile(tagged, options.SurfacesPath, error));
}

// Whether every file the run writes can be written: found out now, not after a long run.
bool CanWriteOutputs(const CommandLineOptions& options, std::string& error)
{
  std::vector<std::string> written = options.Outputs;
  written.push_back(options.ReportPath);
  written.push_back(options.SurfacesPath);
  return std::all_of(written.begin(), written.end(),
    [&](const std::string& path) { return path.empty() || CanWriteBeside(path, error); });
}

// The meshing stages, kept together so that each one's output lives as long as the run.
struct MeshingStages
{
  vtkNew<vtkCBC3DBCCLattice> Lattice;
  vtkNew<vtkCBC3DRefinement> Refinement;
  vtkNew<vtkCBC3DDeformation> Deformation;
  vtkNew<vtkCBC3DMeshQuality> Quality;
};

// Chains the stages the options ask for on `image`: the lattice, refinement (a fidelity above
// 0), deformation (iterations above 0), and the quality filter on the last of them.
void ConfigureStages(MeshingStages& stages, vtkImageData* image, const CommandLineOptions& options)
{
  // The lattice and refinement keep the budget; refinement splits to the edge limits and
  // deformation stretches no edge past them.
  for (vtkCBC3DAlgorithm* stage :
    std::initializer_list<vtkCBC3DAlgorithm*>{ stages.Lattice, stages.Refinement, stages.Deformation })
  {
    stage->SetMaximumNumberOfTets(options.MaxTets);
    stage->SetMaximumEdgeLength(options.MaxEdge);
    for (const auto& [label, length] : options.TissueMaxEdge)
      stage->SetTissueMaximumEdgeLength(static_cast<double>(label), length);
  }
  stages.Lattice->SetInputData(image);
  stages.Lattice->SetEdgeLength(options.BCCSize);
  vtkAlgorithm* last = stages.Lattice;
  stages.Refinement->SetFidelity(options.Fidelity);
  stages.Refinement->SetBoundaryDistance(options.BoundaryDistance);
  stages.Refinement->SetMinimumEdgeLength(options.MinEdge);
  for (const auto& [label, fidelity] : options.TissueFidelity)
    stages.Refinement->SetTissueFidelity(static_cast<double>(label), fidelity);
  if (stages.Refinement->AsksForRefinement())
  {
    stages.Refinement->SetInputConnection(last->GetOutputPort());
    stages.Refinement->SetImageData(image);
    last = stages.Refinement;
  }
  if (options.Iterations > 0)
  {
    stages.Deformation->SetInputConnection(last->GetOutputPort());
    stages.Deformation->SetImageData(image);
    stages.Deformation->SetIterations(options.Iterations);
    stages.Deformation->SetPattern(PatternValue(options.Pattern));
    stages.Deformation->SetTargetPlacement(
      options.Targets == "face" ? vtkCBC3DDeformation::VOXEL_FACE : vtkCBC3DDeformation::VOXEL_CENTRE);
    stages.Deformation->SetKeepVolumes(options.KeepVolumes);
    last = stages.Deformation;
  }
  stages.Quality->SetInputConnection(last->GetOutputPort());
  stages.Quality->SetImageData(image);
  for (vtkCBC3DAlgorithm* stage : std::initializer_list<vtkCBC3DAlgorithm*>{
         stages.Lattice, stages.Refinement, stages.Deformation, stages.Quality })
  {
    SetBackground(stage, options);
    stage->SetNumberOfThreads(options.Threads);
  }
}

// Runs the configured stages one by one (each timed in the report); the measured mesh, or null
// with `error` when a stage fails or is stopped.
vtkUnstructuredGrid* RunStages(
  MeshingStages& stages, const CommandLineOptions& options, bool showProgress, RunReport& report, std::string& error)
{
  if (!RunStage(stages.Lattice, "lattice", showProgress, report, error))
  {
    return nullptr;
  }
  vtkDataArray* edge = stages.Lattice->GetOutput()->GetFieldData()->GetArray(vtkCBC3DArrayNames::LatticeEdgeLength);
  report.BCCSizeUsed = edge ? edge->GetTuple1(0) : options.BCCSize;
  if ((stages.Refinement->AsksForRefinement() && !RunStage(stages.Refinement, "refinement", showProgress, report, error)) ||
    (options.Iterations > 0 && !RunStage(stages.Deformation, "deformation", showProgress, report, error)) ||
    !RunStage(stages.Quality, "quality", showProgress, report, error))
  {
    return nullptr;
  }
  vtkUnstructuredGrid* mesh = stages.Quality->GetOutput();
  if (!CollectQuality(mesh, report))
  {
    error = "the quality filter produced no figures";
    return nullptr;
  }
  return mesh;
}

int Run(int argc, char* argv[])
{
  CommandLineOptions options;
  std::string error;
  if (!ParseCommandLine(argc, argv, options, error))
  {
    return Fail(error, 2);
  }
  if (options.ShowHelp || options.ShowVersion)
  {
    std::cout << (options.ShowHelp ? UsageText() : std::string("cbc3d ") + CBC3D_VERSION + "\n") << std::flush;
    return 0;
  }
  SilenceVtkMessages();
  if (!CanWriteOutputs(options, error))
  {
    return Fail(error);
  }
  if (!cbc3d::StartThreads(options.Threads))
  {
    return Fail("out of memory: cannot start " + std::to_string(cbc3d::ThreadCount(options.Threads)) +
      " threads; try fewer (--threads)");
  }
  const bool showProgress = !options.Quiet && isatty(fileno(stderr));
  RunReport report;
  report.Options = options;
  Stopwatch total;
  Stopwatch readClock;
  vtkSmartPointer<vtkImageData> image = ReadImageFile(options.Input, error);
  if (!image)
  {
    return Fail(error);
  }
  report.Seconds.emplace_back("read", readClock.Seconds());
  MeshingStages stages;
  ConfigureStages(stages, image, options);
  vtkUnstructuredGrid* mesh = RunStages(stages, options, showProgress, report, error);
  Stopwatch writeClock;
  if (!mesh || !WriteOutputs(mesh, options, report, error))
  {
    return Fail(error);
  }
  report.Seconds.emplace_back("write", writeClock.Seconds());
  report.Seconds.emplace_back("total", total.Seconds());
  if (!options.ReportPath.empty() && !WriteTextFile(FormatJson(report), options.ReportPath, error))
  {
    return Fail(error);
  }
  KeepRunFiles();
  if (!options.Quiet)
  {
    std::cout << FormatSummary(report) << std::flush;
  }
  return 0;
}

// glibc hands large freed blocks back to the kernel at once, so every refinement pass and
// deformation round faults the pages of its new arrays in again (several microseconds a page
// on a virtual machine: a tenth of a run's time on the heads). Keeping freed memory for reuse
// halves the page faults; the peak grows by about 2%.
void KeepFreedMemory()
{
  mallopt(M_MMAP_THRESHOLD, 32 * 1024 * 1024); // glibc's largest: bigger blocks are still mapped
  mallopt(M_TRIM_THRESHOLD, 1024 * 1024 * 1024);
}
} // namespace

int main(int argc, char* argv[])
{
  KeepFreedMemory();
  // A run too large for the machine ends with a message, not an abort; the output, written to
  // a temporary file and renamed only when whole, is not left half-made.
  InstallStopHandlers();
  ReleaseHeldSignals(); // a stop signal sent while the launcher started this program: now
  try
  {
    return Run(argc, argv);
  }
  catch (const std::bad_alloc&)
  {
    return Fail("out of memory: try a larger --bcc-size, or a machine with more memory");
  }
  catch (const std::exception& e)
  {
    return Fail(std::string("unexpected error: ") + e.what());
  }
}
