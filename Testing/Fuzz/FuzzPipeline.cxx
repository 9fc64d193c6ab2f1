// libFuzzer target: the whole core pipeline (lattice, refinement, deformation, quality and the
// tagged mesh of the exporters) on a small label image decoded from the input, with the mesh
// invariants checked after every stage. Images are at most 12 x 12 x 12 voxels and lattices
// at least 1.5 voxels, so that one input runs in well under a second.
#include "FuzzBytes.h"
#include "MeshInvariants.h"

#include "cbc3d/base/TaggedMesh.h"
#include "cbc3d/deformation/Deformation.h"
#include "cbc3d/lattice/BCCLattice.h"
#include "cbc3d/quality/ImageTopology.h"
#include "cbc3d/quality/MeshTopology.h"
#include "cbc3d/quality/Quality.h"
#include "cbc3d/refinement/Refinement.h"
#include "cbc3d/sampling/SurfacePoints.h"

#include <cstddef>
#include <cstdint>
#include <string>

namespace
{
// Label values the image draws from: background 0 first, then tissues with awkward values
// (negative, large, not contiguous) that must reach the output unchanged.
constexpr std::int32_t LabelChoices[] = { 0, 1, 2, 7, -3, 128, 100000 };
constexpr int LabelChoiceCount = sizeof(LabelChoices) / sizeof(LabelChoices[0]);

// The direction matrix: identity, a reflection of x, or an axis permutation with a reflection.
Eigen::Matrix3d DecodeDirection(int choice)
{
  Eigen::Matrix3d direction = Eigen::Matrix3d::Identity();
  if (choice == 1)
  {
    direction(0, 0) = -1.0;
  }
  else if (choice == 2)
  {
    direction << 0, 1, 0, 0, 0, 1, -1, 0, 0;
  }
  return direction;
}

// Header bytes (dimensions, spacing, frame, label count), then one byte per voxel, x fastest.
cbc3d::LabelImage DecodeImage(FuzzBytes& bytes)
{
  cbc3d::LabelImage image;
  for (int a = 0; a < 3; ++a)
  {
    image.Dimensions[a] = 2 + bytes.Pick(11);
  }
  for (int a = 0; a < 3; ++a)
  {
    image.Spacing[a] = 0.25 * (1 + bytes.Pick(16)); // 0.25 .. 4 mm
  }
  image.Direction = DecodeDirection(bytes.Pick(3));
  image.Origin = Eigen::Vector3d(bytes.Next(), bytes.Next(), bytes.Next()) - Eigen::Vector3d::Constant(128.0);
  if (bytes.Pick(4) == 0)
  {
    image.BackgroundLabels = { 0, LabelChoices[1 + bytes.Pick(LabelChoiceCount - 1)] };
  }
  const int labelCount = 2 + bytes.Pick(LabelChoiceCount - 1);
  image.Labels.resize(static_cast<std::size_t>(image.VoxelCount()));
  for (std::int32_t& label : image.Labels)
  {
    label = LabelChoices[bytes.Pick(labelCount)];
  }
  return image;
}

struct PipelineParams
{
  cbc3d::LatticeParams Lattice;
  cbc3d::RefinementParams Refinement;
  cbc3d::DeformationParams Deformation;
};

PipelineParams DecodeParams(FuzzBytes& bytes, const cbc3d::LabelImage& image)
{
  PipelineParams params;
  const double finest = image.Spacing.minCoeff();
  params.Lattice.EdgeLength = finest * (1.5 + 0.5 * bytes.Pick(14)); // 1.5 .. 8 spacings
  params.Lattice.NumberOfThreads = 1;
  const double fidelities[] = { 0.0, 0.5, 0.8, 0.95, 1.0 };
  params.Refinement.Fidelity = fidelities[bytes.Pick(5)];
  params.Refinement.BoundaryDistance = bytes.Pick(3) == 0 ? -1.0 : 0.0;
  params.Refinement.SoundLabels = bytes.Pick(4) != 0;
  params.Refinement.NumberOfThreads = 1;
  params.Deformation.Iterations = bytes.Pick(4);
  params.Deformation.Pattern = static_cast<cbc3d::TargetPattern>(bytes.Pick(4));
  params.Deformation.Placement =
    bytes.Pick(2) ? cbc3d::TargetPlacement::VoxelFace : cbc3d::TargetPlacement::VoxelCentre;
  params.Deformation.KeepVolumes = bytes.Pick(2) != 0;
  params.Deformation.NumberOfThreads = 1;
  return params;
}

// The quality stage and the exporters' tagged mesh: their figures are not checked here (the
// unit tests do), only that they run cleanly and agree with the mesh.
void MeasureQuality(const cbc3d::LabelImage& image, const cbc3d::TetMesh& mesh)
{
  const cbc3d::QualitySummary quality = cbc3d::SummarizeQuality(mesh, 1);
  if (quality.Overall.Inverted != 0 || quality.Overall.Tets != std::int64_t(mesh.Tets.size()))
  {
    FailInvariant("quality", "inverted tets, or a tet count other than the mesh's");
  }
  cbc3d::TissueMeshVolumes(mesh);
  cbc3d::TissueImageVolumes(image);
  cbc3d::TissueSurfaceVertices(mesh);
  cbc3d::TissueBoundaryVoxelCentres(image, 1);
  cbc3d::MeasureMeshTopology(mesh);
  cbc3d::MeasureImageTopology(image, 1);
  cbc3d::TaggedMesh tagged;
  const cbc3d::Status status = cbc3d::BuildTaggedMesh(mesh, image.BackgroundLabels[0], tagged);
  if (!status.IsOk())
  {
    FailInvariant("tagged mesh", status.GetMessage());
  }
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  FuzzBytes bytes(data, size);
  const cbc3d::LabelImage image = DecodeImage(bytes);
  const PipelineParams params = DecodeParams(bytes, image);
  if (!cbc3d::ValidateLabelImage(image).IsOk())
  {
    return 0; // no tissue: the filters refuse such an image before the core runs
  }

  cbc3d::TetMesh lattice;
  if (!cbc3d::BuildBCCLattice(image, params.Lattice, lattice).IsOk())
  {
    return 0;
  }
  CheckMeshInvariants(image, lattice, "lattice");

  cbc3d::TetMesh refined = lattice;
  if (params.Refinement.Fidelity > 0.0)
  {
    cbc3d::RefinementResult refinement;
    const cbc3d::Status status = cbc3d::RefineMesh(image, lattice, params.Refinement, refined, refinement);
    if (!status.IsOk())
    {
      return 0;
    }
    CheckMeshInvariants(image, refined, "refinement");
    if (refinement.Levels.size() != refined.Tets.size())
    {
      FailInvariant("refinement", "not one red level per tet");
    }
    if (params.Refinement.SoundLabels && !cbc3d::MeasureMeshTopology(refined).SolverReady())
    {
      FailInvariant("refinement", "sound labels asked, but a hinge or a non-manifold surface is left");
    }
  }
  if (refined.Tets.empty())
  {
    return 0;
  }

  cbc3d::TetMesh deformed = refined;
  if (params.Deformation.Iterations > 0)
  {
    cbc3d::DeformationResult deformation;
    const cbc3d::Status status = cbc3d::DeformMesh(image, refined, params.Deformation, deformed, deformation);
    if (!status.IsOk())
    {
      return 0;
    }
    CheckMeshInvariants(image, deformed, "deformation");
    CheckSameTopology(refined, deformed, "deformation");
  }
  MeasureQuality(image, deformed);
  return 0;
}
