#ifndef cbc3d_GeometryOnlyFormats_h
#define cbc3d_GeometryOnlyFormats_h

#include <string>

class vtkPolyData;

/// The triangles of `surfaces` as a binary STL file's bytes (a facet normal from each
/// triangle's winding) and as Wavefront OBJ text (vertices and faces), made in memory so that
/// the caller writes them out with every write checked: VTK's STL and OBJ writers write only to
/// a file, and its OBJ writer does not report a failed write.
std::string StlBytes(vtkPolyData* surfaces);
std::string ObjText(vtkPolyData* surfaces);

#endif
