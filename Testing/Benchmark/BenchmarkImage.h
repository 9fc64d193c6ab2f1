#ifndef cbc3d_BenchmarkImage_h
#define cbc3d_BenchmarkImage_h

#include "vtkCBC3DNIfTIReader.h"

#include <vtkSmartPointer.h>

#include <chrono>
#include <cstdio>
#include <string>
#include <sys/stat.h>

// What the benchmarks share: a clock and the real images, which live outside the repository.

/// Seconds since `start`.
inline double Seconds(const std::chrono::steady_clock::time_point& start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// A reader that has read the image at `path`; null, after saying so, when there is no such
/// file.
inline vtkSmartPointer<vtkCBC3DNIfTIReader> ReadBenchmarkImage(const std::string& path)
{
  struct stat info;
  if (stat(path.c_str(), &info) != 0)
  {
    std::printf("skipped: %s not found (the real images live in ../shared/data)\n", path.c_str());
    return nullptr;
  }
  auto reader = vtkSmartPointer<vtkCBC3DNIfTIReader>::New();
  reader->SetFileName(path.c_str());
  reader->Update();
  return reader;
}

#endif
