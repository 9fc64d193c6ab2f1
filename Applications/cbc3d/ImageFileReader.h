#ifndef cbc3d_ImageFileReader_h
#define cbc3d_ImageFileReader_h

#include <vtkImageData.h>
#include <vtkSmartPointer.h>

#include <string>

/// Reads a label image with the VTK reader its extension names (.nii/.nii.gz in their world
/// frame, .nrrd/.nhdr, .mha/.mhd, .vti). Returns null with a one-line message on failure.
vtkSmartPointer<vtkImageData> ReadImageFile(const std::string& path, std::string& error);

#endif
