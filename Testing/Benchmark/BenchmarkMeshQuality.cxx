// Prints how long the quality filter (angles, topology, distances) takes on a mesh of about a
// million tets of the shared brain image, with 1 thread and with all cores, beside the lattice
// that made the mesh. Asserts
// nothing: machines are shared and noisy, so read the figures and their ratios.
//   CBC3DBenchmarkMeshQuality [IMAGE.nii.gz] [LATTICE_MM]
#include "BenchmarkImage.h"

#include "vtkCBC3DBCCLattice.h"
#include "vtkCBC3DMeshQuality.h"

#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkUnstructuredGrid.h>

#include <omp.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

int main(int argc, char* argv[])
{
  const std::string defaultImage = std::string(CBC3D_SHARED_DATA) + "/cbc3d-brain.nii.gz";
  const std::string path = argc > 1 ? argv[1] : defaultImage;
  const double edge = argc > 2 ? std::atof(argv[2]) : 2.67; // about 1 M tets on the brain
  const auto reader = ReadBenchmarkImage(path);
  if (!reader)
  {
    return 0;
  }

  vtkNew<vtkCBC3DBCCLattice> lattice;
  lattice->SetInputConnection(reader->GetOutputPort());
  lattice->SetEdgeLength(edge);
  auto start = std::chrono::steady_clock::now();
  lattice->Update();
  const double latticeSeconds = Seconds(start);
  vtkUnstructuredGrid* mesh = lattice->GetOutput();
  std::printf("image %s, lattice %.2f mm: %lld tets, %lld points, %.3f s (all %d cores)\n",
    path.c_str(), edge, static_cast<long long>(mesh->GetNumberOfCells()),
    static_cast<long long>(mesh->GetNumberOfPoints()), latticeSeconds, omp_get_max_threads());

  double oneThread = 0.0;
  for (const int threads : { 1, 0 })
  {
    for (const bool withImage : { false, true })
    {
      vtkNew<vtkCBC3DMeshQuality> quality;
      quality->SetInputData(mesh);
      if (withImage)
      {
        quality->SetImageConnection(reader->GetOutputPort());
      }
      quality->SetNumberOfThreads(threads);
      start = std::chrono::steady_clock::now();
      quality->Update();
      const double seconds = Seconds(start);
      if (threads == 1 && withImage)
      {
        oneThread = seconds;
      }
      vtkFieldData* fields = quality->GetOutput()->GetFieldData();
      std::printf("quality %-16s %-11s %.3f s   angles %.2f-%.2f deg", withImage ? "with distances," : "angles only,",
        threads == 1 ? "1 thread:" : "all cores:", seconds,
        fields->GetArray("MinDihedralAngle")->GetTuple1(0), fields->GetArray("MaxDihedralAngle")->GetTuple1(0));
      if (vtkDataArray* hd = fields->GetArray("HausdorffDistance"))
      {
        std::printf(", Hausdorff %.3f mm", hd->GetTuple1(0));
      }
      // The topology is part of every run's time: show what it found.
      std::printf(", %lld / %lld pieces (face / vertex), Euler %lld",
        static_cast<long long>(fields->GetArray("FaceComponents")->GetTuple1(0)),
        static_cast<long long>(fields->GetArray("VertexComponents")->GetTuple1(0)),
        static_cast<long long>(fields->GetArray("SurfaceEuler")->GetTuple1(0)));
      if (threads == 0 && withImage && seconds > 0.0)
      {
        std::printf(", %.2fx faster than 1 thread", oneThread / seconds);
      }
      std::printf("\n");
    }
  }
  return 0;
}
