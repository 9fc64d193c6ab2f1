#ifndef cbc3d_MeshInvariants_h
#define cbc3d_MeshInvariants_h

#include "cbc3d/base/LabelImage.h"
#include "cbc3d/base/TetMesh.h"

#include <string>

// What every stage of the pipeline guarantees about its mesh, checked after each stage by the
// pipeline fuzzer. A violation prints the stage and the broken rule and aborts, so that
// libFuzzer records the input as a crash.

/// Valid indices, one label per tet, every tet positively oriented (ValidateTetMesh), finite
/// points, and only tissue labels of the image on the tets.
void CheckMeshInvariants(const cbc3d::LabelImage& image, const cbc3d::TetMesh& mesh, const char* stage);

/// Deformation moves points only: the same tets with the same labels.
void CheckSameTopology(const cbc3d::TetMesh& before, const cbc3d::TetMesh& after, const char* stage);

/// Prints "cbc3d fuzz: <stage>: <message>" and aborts.
[[noreturn]] void FailInvariant(const char* stage, const std::string& message);

#endif
