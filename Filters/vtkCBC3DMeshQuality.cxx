#include "vtkCBC3DMeshQuality.h"

#include "vtkCBC3DArrayNames.h"
#include "vtkCBC3DConvert.h"
#include "vtkCBC3DLabelValues.h"

#include "cbc3d/base/Parallel.h"
#include "cbc3d/base/PointGrid.h"
#include "cbc3d/quality/MeshTopology.h"
#include "cbc3d/quality/Quality.h"
#include "cbc3d/quality/SurfaceDistance.h"
#include "cbc3d/sampling/SurfacePoints.h"

#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIdTypeArray.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointSet.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <utility>
#include <functional>
#include <map>
#include <vector>

vtkStandardNewMacro(vtkCBC3DMeshQuality);

namespace
{
constexpr double NaN = std::numeric_limits<double>::quiet_NaN();

template <typename ArrayT, typename ValueT>
void AddFieldArray(vtkFieldData* fields, const char* name, const std::vector<ValueT>& values)
{
  vtkNew<ArrayT> array;
  array->SetName(name);
  array->SetNumberOfValues(static_cast<vtkIdType>(values.size()));
  for (std::size_t i = 0; i < values.size(); ++i)
  {
    array->SetValue(static_cast<vtkIdType>(i), values[i]);
  }
  fields->AddArray(array);
}

void AddCellArray(vtkUnstructuredGrid* grid, const char* name, const std::vector<double>& values)
{
  vtkNew<vtkDoubleArray> array;
  array->SetName(name);
  array->SetNumberOfValues(static_cast<vtkIdType>(values.size()));
  std::copy(values.begin(), values.end(), array->GetPointer(0));
  grid->GetCellData()->AddArray(array);
}

// Distance from every point of `from` to the nearest of `to` (gridded), on `threads` threads.
std::vector<double> NearestDistances(const std::vector<Eigen::Vector3d>& from, const cbc3d::PointGrid& grid,
  const std::vector<Eigen::Vector3d>& to, int threads)
{
  const std::vector<int> nearest = grid.NearestAnyOfAll(from, threads);
  std::vector<double> distances(from.size());
  for (std::size_t i = 0; i < from.size(); ++i)
    distances[i] = (from[i] - to[nearest[i]]).norm();
  return distances;
}

// The topology arrays: the whole body's, then one value per tissue row (`labels`, ascending).
// `image` is null without the label image.
void AddTopologyFields(vtkFieldData* fields, const cbc3d::MeshTopology& topology,
  const cbc3d::ImageTopology* image, const std::vector<std::int32_t>& labels)
{
  namespace names = vtkCBC3DArrayNames;
  const cbc3d::RegionTopology& whole = topology.Whole;
  // A solver meets every tissue's surface defects as well as the body's.
  vtkIdType edges = whole.NonManifoldEdges, vertices = whole.NonManifoldVertices;
  for (const auto& entry : topology.Tissues)
  {
    edges += entry.second.NonManifoldEdges;
    vertices += entry.second.NonManifoldVertices;
  }
  auto one = [fields](const char* name, vtkIdType value) {
    AddFieldArray<vtkIdTypeArray>(fields, name, std::vector<vtkIdType>{ value });
  };
  one(names::FaceComponents, whole.FaceComponents);
  one(names::VertexComponents, whole.VertexComponents);
  one(names::HingedParts, whole.HingedParts);
  one(names::NonManifoldEdges, edges);
  one(names::NonManifoldVertices, vertices);
  one(names::SurfaceEuler, whole.SurfaceEuler);
  one(names::SolverReady, topology.SolverReady() ? 1 : 0);
  if (image)
  {
    one(names::ImageSurfaceEuler, image->WholeSurfaceEuler);
    one(names::ImagePinchesJoinedEuler, image->WholePinchesJoinedEuler());
    one(names::ImagePinchesPartedEuler, image->WholePinchesPartedEuler);
  }

  // One value per tissue row; a tissue the mesh lacks is the empty set's zeros.
  auto addColumn = [&](const char* name, const std::function<vtkIdType(int)>& valueOf) {
    std::vector<vtkIdType> values;
    for (const int label : labels)
    {
      values.push_back(valueOf(label));
    }
    AddFieldArray<vtkIdTypeArray>(fields, name, values);
  };
  using Field = std::int64_t cbc3d::RegionTopology::*;
  const std::pair<const char*, Field> columns[] = {
    { names::TissueFaceComponents, &cbc3d::RegionTopology::FaceComponents },
    { names::TissueVertexComponents, &cbc3d::RegionTopology::VertexComponents },
    { names::TissueHingedParts, &cbc3d::RegionTopology::HingedParts },
    { names::TissueNonManifoldEdges, &cbc3d::RegionTopology::NonManifoldEdges },
    { names::TissueNonManifoldVertices, &cbc3d::RegionTopology::NonManifoldVertices },
    { names::TissueSurfaceEuler, &cbc3d::RegionTopology::SurfaceEuler },
  };
  for (const auto& [name, field] : columns)
  {
    addColumn(name, [&, field = field](int label) {
      const auto found = topology.Tissues.find(label);
      return found == topology.Tissues.end() ? 0 : found->second.*field;
    });
  }
  if (image)
  {
    // A tissue the image lacks has no voxels: Euler 0 every way.
    auto has = [image](int label) { return image->TissueSurfaceEuler.count(label) > 0; };
    addColumn(names::TissueImageSurfaceEuler,
      [&](int label) { return has(label) ? image->TissueSurfaceEuler.at(label) : 0; });
    addColumn(names::TissueImagePinchesJoinedEuler,
      [&](int label) { return has(label) ? image->TissuePinchesJoinedEuler(label) : 0; });
    addColumn(names::TissueImagePinchesPartedEuler,
      [&](int label) { return has(label) ? image->TissuePinchesPartedEuler.at(label) : 0; });
  }
}

// One row of the per-tissue table.
struct TissueRow
{
  int Label = 0;
  cbc3d::DihedralSummary Angles;
  cbc3d::SurfaceDistanceSummary Distances = { NaN, NaN, NaN, NaN, NaN };
  std::size_t DistanceCount = 0; // points behind the mean
  // The directed distances themselves: the whole mesh's 95th percentile is taken over every
  // tissue's samples, not the largest of the tissues' percentiles.
  std::vector<double> MeshToImage, ImageToMesh;
};

// The two-sided distances between a tissue's surface vertices and its boundary voxel centres
// (grids of cells of about a voxel; a grid over few points widens its own cells).
void MeasureDistances(const cbc3d::TetMesh& mesh, const std::vector<cbc3d::PointId>& surface,
  const std::vector<Eigen::Vector3d>& boundary, double voxelSize, int threads, TissueRow& row)
{
  std::vector<Eigen::Vector3d> meshPoints;
  meshPoints.reserve(surface.size());
  for (const cbc3d::PointId id : surface)
  {
    meshPoints.push_back(mesh.Points[id]);
  }
  const cbc3d::PointGrid meshGrid(meshPoints, voxelSize, threads), imageGrid(boundary, voxelSize, threads);
  std::vector<double> meshToImage = NearestDistances(meshPoints, imageGrid, boundary, threads);
  std::vector<double> imageToMesh = NearestDistances(boundary, meshGrid, meshPoints, threads);
  row.DistanceCount = meshToImage.size() + imageToMesh.size();
  row.Distances = cbc3d::SummarizeSurfaceDistances(meshToImage, imageToMesh);
  row.MeshToImage = std::move(meshToImage);
  row.ImageToMesh = std::move(imageToMesh);
}

// The 95th percentile of every tissue's surface samples together (the Hausdorff measure's
// summary for the whole mesh); NaN where a tissue lies on one side only.
double PooledPercentile95(const std::vector<TissueRow>& rows)
{
  std::vector<const std::vector<double>*> meshToImage, imageToMesh;
  for (const TissueRow& row : rows)
  {
    if (std::isnan(row.Distances.Percentile95))
      return NaN;
    meshToImage.push_back(&row.MeshToImage);
    imageToMesh.push_back(&row.ImageToMesh);
  }
  return rows.empty() ? NaN : cbc3d::SummarizeSurfaceDistancesTogether(meshToImage, imageToMesh).Percentile95;
}

// The whole mesh's counts and angle extremes.
void AddOverallFields(vtkFieldData* fields, const cbc3d::DihedralSummary& all)
{
  namespace names = vtkCBC3DArrayNames;
  const bool empty = all.Tets == 0;
  AddFieldArray<vtkIdTypeArray>(fields, names::TetCount, std::vector<vtkIdType>{ all.Tets });
  AddFieldArray<vtkIdTypeArray>(fields, names::InvertedTetCount, std::vector<vtkIdType>{ all.Inverted });
  AddFieldArray<vtkIdTypeArray>(fields, names::SmallAngleTetCount, std::vector<vtkIdType>{ all.SmallAngle });
  AddFieldArray<vtkIdTypeArray>(fields, names::LargeAngleTetCount, std::vector<vtkIdType>{ all.LargeAngle });
  AddFieldArray<vtkDoubleArray>(fields, names::MinDihedralAngle, std::vector<double>{ empty ? NaN : all.MinDegrees });
  AddFieldArray<vtkDoubleArray>(fields, names::MaxDihedralAngle, std::vector<double>{ empty ? NaN : all.MaxDegrees });
}

double VolumeOf(const std::map<std::int32_t, double>& volumes, int label)
{
  const auto found = volumes.find(label);
  return found == volumes.end() ? 0.0 : found->second;
}

// One value per tissue row for counts, angles and volumes; with the image, its volumes and the
// distances, per tissue and for the whole mesh.
void AddTissueFields(vtkFieldData* fields, const std::vector<TissueRow>& rows,
  const std::map<std::int32_t, double>& meshVolumes, const std::map<std::int32_t, double>* imageVolumes,
  const cbc3d::LabelCodes& codes)
{
  namespace names = vtkCBC3DArrayNames;
  std::vector<std::int32_t> labels;
  std::vector<vtkIdType> tets, inverted, small, large;
  std::vector<double> minima, maxima, hausdorff, meshToImage, imageToMesh, hausdorff95, mean, volume, imageVolume;
  double meshHausdorff = rows.empty() ? NaN : 0.0;
  double distanceSum = 0.0;
  std::size_t distanceCount = 0;
  for (const TissueRow& row : rows)
  {
    labels.push_back(row.Label);
    tets.push_back(row.Angles.Tets);
    inverted.push_back(row.Angles.Inverted);
    small.push_back(row.Angles.SmallAngle);
    large.push_back(row.Angles.LargeAngle);
    minima.push_back(row.Angles.MinDegrees);
    maxima.push_back(row.Angles.MaxDegrees);
    volume.push_back(VolumeOf(meshVolumes, row.Label));
    imageVolume.push_back(imageVolumes ? VolumeOf(*imageVolumes, row.Label) : 0.0);
    const cbc3d::SurfaceDistanceSummary& d = row.Distances;
    hausdorff.push_back(d.Hausdorff);
    meshToImage.push_back(d.AToB);
    imageToMesh.push_back(d.BToA);
    hausdorff95.push_back(d.Percentile95);
    mean.push_back(d.Mean);
    // NaN (a tissue on one side only) must win over any finite distance.
    meshHausdorff = std::isnan(d.Hausdorff) ? NaN : std::max(meshHausdorff, d.Hausdorff);
    distanceSum += std::isnan(d.Mean) ? NaN : d.Mean * static_cast<double>(row.DistanceCount);
    distanceCount += row.DistanceCount;
  }
  fields->AddArray(vtkCBC3DLabelValues::FromCodes(labels, codes, names::TissueLabel));
  AddFieldArray<vtkIdTypeArray>(fields, names::TissueTetCount, tets);
  AddFieldArray<vtkIdTypeArray>(fields, names::TissueInvertedTetCount, inverted);
  AddFieldArray<vtkIdTypeArray>(fields, names::TissueSmallAngleTetCount, small);
  AddFieldArray<vtkIdTypeArray>(fields, names::TissueLargeAngleTetCount, large);
  AddFieldArray<vtkDoubleArray>(fields, names::TissueMinDihedralAngle, minima);
  AddFieldArray<vtkDoubleArray>(fields, names::TissueMaxDihedralAngle, maxima);
  AddFieldArray<vtkDoubleArray>(fields, names::TissueVolume, volume);
  if (imageVolumes)
  {
    AddFieldArray<vtkDoubleArray>(fields, names::TissueImageVolume, imageVolume);
    AddFieldArray<vtkDoubleArray>(fields, names::HausdorffDistance, std::vector<double>{ meshHausdorff });
    AddFieldArray<vtkDoubleArray>(fields, names::HausdorffDistance95, std::vector<double>{ PooledPercentile95(rows) });
    AddFieldArray<vtkDoubleArray>(fields, names::MeanSurfaceDistance,
      std::vector<double>{ distanceCount ? distanceSum / double(distanceCount) : NaN });
    AddFieldArray<vtkDoubleArray>(fields, names::TissueHausdorffDistance, hausdorff);
    AddFieldArray<vtkDoubleArray>(fields, names::TissueMeshToImageDistance, meshToImage);
    AddFieldArray<vtkDoubleArray>(fields, names::TissueImageToMeshDistance, imageToMesh);
    AddFieldArray<vtkDoubleArray>(fields, names::TissueHausdorffDistance95, hausdorff95);
    AddFieldArray<vtkDoubleArray>(fields, names::TissueMeanSurfaceDistance, mean);
  }
}
// A row per tissue of the mesh, and of the image when there is one (`image` may be null);
// false when the user stopped the filter.
bool MeasureTissues(vtkCBC3DMeshQuality* filter, const cbc3d::TetMesh& mesh, const std::vector<cbc3d::MeshFace>& faces,
  const cbc3d::QualitySummary& summary, const cbc3d::LabelImage* image, std::vector<TissueRow>& rows)
{
  std::set<int> labels;
  for (const auto& entry : summary.Tissues)
  {
    labels.insert(entry.first);
  }
  std::map<std::int32_t, std::vector<cbc3d::PointId>> surface;
  std::map<std::int32_t, std::vector<Eigen::Vector3d>> boundary;
  if (image)
  {
    surface = cbc3d::TissueSurfaceVertices(mesh, faces);
    boundary = cbc3d::TissueBoundaryVoxelCentres(*image, filter->GetNumberOfThreads());
    for (const auto& entry : boundary)
    {
      labels.insert(entry.first);
    }
  }
  filter->UpdateProgress(0.5);

  double done = 0.0;
  for (const int label : labels)
  {
    TissueRow row;
    row.Label = label;
    const auto angles = summary.Tissues.find(label);
    if (angles != summary.Tissues.end())
    {
      row.Angles = angles->second;
    }
    else
    {
      row.Angles.MinDegrees = row.Angles.MaxDegrees = NaN;
    }
    const auto meshSide = surface.find(label);
    const auto imageSide = boundary.find(label);
    if (image && (meshSide == surface.end() || imageSide == boundary.end()))
    {
      vtkWarningWithObjectMacro(filter, << "tissue " << image->Codes.ValueOf(label) << " is in the "
                      << (meshSide == surface.end() ? "image but not in the mesh"
                                                    : "mesh but not in the image")
                      << ": its distances are NaN");
    }
    else if (image)
    {
      MeasureDistances(mesh, meshSide->second, imageSide->second, image->Spacing.maxCoeff(),
        filter->GetNumberOfThreads(), row);
    }
    rows.push_back(row);
    done += 1.0;
    filter->UpdateProgress(0.5 + 0.5 * done / static_cast<double>(labels.size()));
    if (filter->CheckAbort())
    {
      return false;
    }
  }
  return true;
}
} // namespace

vtkCBC3DMeshQuality::vtkCBC3DMeshQuality()
  : vtkCBC3DAlgorithm(ImageInput::OptionalPort1)
{
}

int vtkCBC3DMeshQuality::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkUnstructuredGrid* input = vtkUnstructuredGrid::GetData(inputVector[0]);
  vtkUnstructuredGrid* output = vtkUnstructuredGrid::GetData(outputVector);
  const bool withImage = this->HasImage(inputVector);

  cbc3d::TetMesh mesh;
  std::shared_ptr<const cbc3d::LabelImage> image;
  cbc3d::LabelCodes meshCodes;
  const bool read = withImage ? this->ReadMeshAndImage(inputVector, mesh, image)
                              : this->ReadMesh(inputVector, mesh, meshCodes);
  if (!read)
  {
    return 0;
  }
  this->UpdateProgress(0.05);

  cbc3d::TetDihedralExtremes perTet;
  const cbc3d::QualitySummary summary =
    cbc3d::SummarizeQuality(mesh, this->NumberOfThreads, &perTet);
  this->UpdateProgress(0.3);

  // One face list for the tissue surfaces and the topology.
  const std::vector<cbc3d::MeshFace> faces = cbc3d::FindMeshFaces(mesh, this->NumberOfThreads);
  std::vector<TissueRow> rows;
  if (!MeasureTissues(this, mesh, faces, summary, image.get(), rows))
  {
    output->Initialize();
    return 1; // stopped by the user
  }

  output->ShallowCopy(input);
  AddCellArray(output, vtkCBC3DArrayNames::MinDihedralAngle, perTet.MinDegrees);
  AddCellArray(output, vtkCBC3DArrayNames::MaxDihedralAngle, perTet.MaxDegrees);
  vtkNew<vtkFieldData> fields;
  fields->DeepCopy(input->GetFieldData());
  AddOverallFields(fields, summary.Overall);
  const auto imageVolumes = withImage ? cbc3d::TissueImageVolumes(*image, this->NumberOfThreads) : std::map<std::int32_t, double>();
  AddTissueFields(fields, rows, cbc3d::TissueMeshVolumes(mesh), withImage ? &imageVolumes : nullptr,
    withImage ? image->Codes : meshCodes);
  std::vector<std::int32_t> tissueLabels;
  for (const TissueRow& row : rows)
  {
    tissueLabels.push_back(row.Label);
  }
  const cbc3d::ImageTopology imageTopology =
    withImage ? cbc3d::MeasureImageTopology(*image, this->NumberOfThreads) : cbc3d::ImageTopology();
  AddTopologyFields(fields, cbc3d::MeasureMeshTopology(mesh, faces, this->NumberOfThreads), withImage ? &imageTopology : nullptr, tissueLabels);
  output->SetFieldData(fields);
  this->UpdateProgress(1.0);
  return 1;
}

void vtkCBC3DMeshQuality::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
