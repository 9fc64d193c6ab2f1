// How soon a stop could be seen: runs vtkCBC3DMesher on a label image and prints, per stage,
// the longest time between two of its progress events (each one is a chance for ParaView to
// deliver a stop request: the stages poll for an abort with every report). With --stop-at T
// it also asks for a stop T seconds in, as a press of ParaView's stop button would, and
// prints how long the run took to end after it and whether the output was left empty.
// Asserts nothing: the figures depend on the machine and its load.
//   CBC3DBenchmarkStopLatency [IMAGE.nii.gz] [--bcc-size MM] [--background L]... [--stop-at T]
#include "BenchmarkImage.h"

#include "vtkCBC3DMesher.h"

#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkNew.h>
#include <vtkUnstructuredGrid.h>

#include <omp.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

namespace
{
using Clock = std::chrono::steady_clock;

struct Gap
{
  double Length = 0.0; // seconds
  double From = 0.0;   // progress of the mesher at both ends
  double To = 0.0;
};

struct Recorder
{
  vtkCBC3DMesher* Mesher = nullptr;
  Clock::time_point Start = Clock::now();
  Clock::time_point Last = Start;
  double LastProgress = 0.0;
  std::vector<std::string> Order;
  std::map<std::string, Gap> Largest;
  double StopAt = -1.0; // seconds after the start; < 0: never
  bool Stopped = false;

  void Note(const std::string& stage, double progress)
  {
    const Clock::time_point now = Clock::now();
    // A gap belongs to the stage it ends in: that stage's work kept the events away.
    if (!this->Largest.count(stage))
    {
      this->Order.push_back(stage);
    }
    Gap& largest = this->Largest[stage];
    const double seconds = std::chrono::duration<double>(now - this->Last).count();
    if (seconds > largest.Length)
    {
      largest = Gap{ seconds, this->LastProgress, progress };
    }
    this->Last = now;
    this->LastProgress = progress;
    // The press happens at StopAt; ParaView sees it at the first event after that.
    if (this->StopAt >= 0.0 && !this->Stopped && Seconds(this->Start) >= this->StopAt)
    {
      this->Stopped = true;
      this->Mesher->SetAbortExecute(1);
    }
  }

  static void OnProgress(vtkObject*, unsigned long, void* clientData, void*)
  {
    auto* self = static_cast<Recorder*>(clientData);
    const char* text = self->Mesher->GetProgressText();
    self->Note(text ? text : "(between stages)", self->Mesher->GetProgress());
  }
};
} // namespace

int main(int argc, char* argv[])
{
  std::string path = std::string(CBC3D_SHARED_DATA) + "/itk-t1-kmeans-labels.nii.gz";
  double edge = 0.0;
  double stopAt = -1.0;
  std::vector<int> background;
  for (int a = 1; a < argc; ++a)
  {
    const std::string arg = argv[a];
    if (arg == "--bcc-size" && a + 1 < argc)
    {
      edge = std::atof(argv[++a]);
    }
    else if (arg == "--background" && a + 1 < argc)
    {
      background.push_back(std::atoi(argv[++a]));
    }
    else if (arg == "--stop-at" && a + 1 < argc)
    {
      stopAt = std::atof(argv[++a]);
    }
    else
    {
      path = arg;
    }
  }
  const auto reader = ReadBenchmarkImage(path);
  if (!reader)
  {
    return 0;
  }

  vtkNew<vtkCBC3DMesher> mesher;
  mesher->SetInputConnection(reader->GetOutputPort());
  mesher->SetEdgeLength(edge);
  if (!background.empty())
  {
    mesher->RemoveAllBackgroundLabels();
    for (const int label : background)
    {
      mesher->AddBackgroundLabel(label);
    }
  }
  Recorder recorder;
  recorder.Mesher = mesher;
  recorder.StopAt = stopAt;
  vtkNew<vtkCallbackCommand> observer;
  observer->SetCallback(&Recorder::OnProgress);
  observer->SetClientData(&recorder);
  mesher->AddObserver(vtkCommand::ProgressEvent, observer);

  recorder.Start = recorder.Last = Clock::now();
  mesher->Update();
  const double total = Seconds(recorder.Start);
  recorder.Note("(end)", 1.0);

  std::printf("image %s, lattice %g mm%s, %d threads: %.2f s, %lld tets\n", path.c_str(), edge,
    edge == 0.0 ? " (auto)" : "", omp_get_max_threads(), total,
    static_cast<long long>(mesher->GetOutput()->GetNumberOfCells()));
  std::printf("longest time without a progress event, by the stage it ended in:\n");
  Gap worst;
  for (const std::string& stage : recorder.Order)
  {
    const Gap& gap = recorder.Largest[stage];
    std::printf("  %-22s %6.3f s  (progress %.3f -> %.3f)\n", stage.c_str(), gap.Length, gap.From, gap.To);
    if (gap.Length > worst.Length)
    {
      worst = gap;
    }
  }
  std::printf("  %-22s %6.3f s\n", "longest overall", worst.Length);
  if (recorder.Stopped)
  {
    const vtkIdType cells = mesher->GetOutput()->GetNumberOfCells();
    std::printf("stop asked at %.2f s: the run ended %.3f s later, output %s (%lld cells)\n", stopAt,
      total - stopAt, cells == 0 ? "empty" : "NOT EMPTY", static_cast<long long>(cells));
  }
  return 0;
}
