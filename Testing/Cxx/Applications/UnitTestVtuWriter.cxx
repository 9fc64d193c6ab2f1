// The .vtu writer against VTK's: the same bytes as vtkXMLUnstructuredGridWriter (inline binary,
// zlib, UInt32 headers), on any number of threads, for synthetic grids with the corners of the
// format (empty arrays, vectors, blocks of exactly 32 KiB) and for the phantoms meshed by cbc3d.
#include "VtuWriter.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkIdTypeArray.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkShortArray.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <iterator>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

namespace
{
std::string VtkBytes(vtkUnstructuredGrid* mesh)
{
  vtkNew<vtkXMLUnstructuredGridWriter> writer;
  writer->SetInputData(mesh);
  writer->WriteToOutputStringOn();
  writer->SetDataModeToBinary();
  writer->SetCompressorTypeToZLib();
  EXPECT_EQ(writer->Write(), 1);
  return writer->GetOutputString();
}

std::string OurBytes(vtkUnstructuredGrid* mesh, int threads)
{
  std::string bytes;
  EXPECT_TRUE(MakeVtuBytes(mesh, threads, bytes)) << "fell back to VTK's writer";
  return bytes;
}

// Ours first on 1 thread, as in cbc3d (the ranges it caches, vectors' L2_NORM_RANGE written as
// an information key, must be VTK's), then VTK's, then ours on 2 threads.
void ExpectVtkBytes(vtkUnstructuredGrid* mesh)
{
  const std::string first = OurBytes(mesh, 1);
  const std::string expected = VtkBytes(mesh);
  for (int threads : { 1, 2 })
  {
    const std::string bytes = threads == 1 ? first : OurBytes(mesh, threads);
    ASSERT_EQ(bytes.size(), expected.size()) << threads << " threads";
    const auto first = std::mismatch(bytes.begin(), bytes.end(), expected.begin()).first;
    EXPECT_TRUE(bytes == expected)
      << threads << " threads; first difference at byte " << first - bytes.begin();
  }
}

template <typename Array>
vtkSmartPointer<Array> Filled(const char* name, int components, vtkIdType tuples, std::mt19937& random)
{
  auto array = vtkSmartPointer<Array>::New();
  if (name)
    array->SetName(name);
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(tuples);
  std::uniform_int_distribution<int> values(-100, 100);
  for (vtkIdType i = 0; i < array->GetNumberOfValues(); ++i)
    array->SetValue(i, static_cast<typename Array::ValueType>(values(random) / 3.0));
  return array;
}

// `pointCount` points, tets over them, arrays of several kinds; 4096 points make 32 KiB of one
// Float64 per point, so that blocks end exactly on the data's end.
vtkSmartPointer<vtkUnstructuredGrid> SyntheticGrid(vtkIdType pointCount, vtkIdType tetCount)
{
  std::mt19937 random(7);
  auto mesh = vtkSmartPointer<vtkUnstructuredGrid>::New();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetData(Filled<vtkDoubleArray>(nullptr, 3, pointCount, random));
  mesh->SetPoints(points);
  vtkNew<vtkCellArray> cells;
  std::uniform_int_distribution<vtkIdType> corner(0, pointCount - 1);
  for (vtkIdType t = 0; t < tetCount; ++t)
  {
    const vtkIdType tet[4] = { corner(random), corner(random), corner(random), corner(random) };
    cells->InsertNextCell(4, tet);
  }
  mesh->SetCells(VTK_TETRA, cells);
  vtkFieldData* fields = mesh->GetFieldData();
  fields->AddArray(Filled<vtkDoubleArray>("Empty", 1, 0, random));
  fields->AddArray(Filled<vtkDoubleArray>("EmptyVectors", 3, 0, random));
  fields->AddArray(Filled<vtkIdTypeArray>("Counts", 1, 5, random));
  fields->AddArray(Filled<vtkIntArray>("Passes", 1, 1, random));
  vtkPointData* pointData = mesh->GetPointData();
  pointData->AddArray(Filled<vtkDoubleArray>("Scalar64", 1, pointCount, random));
  pointData->AddArray(Filled<vtkFloatArray>("Displacement", 3, pointCount, random));
  auto named = Filled<vtkShortArray>("Pairs", 2, pointCount, random);
  named->SetComponentName(0, "first");
  named->SetComponentName(1, "second");
  pointData->AddArray(named);
  pointData->SetScalars(Filled<vtkIntArray>(nullptr, 1, pointCount, random)); // "Scalars_"
  vtkCellData* cellData = mesh->GetCellData();
  cellData->SetScalars(Filled<vtkIntArray>("Label", 1, tetCount, random));
  cellData->AddArray(Filled<vtkUnsignedCharArray>("Level", 1, tetCount, random));
  cellData->AddArray(Filled<vtkFloatArray>(nullptr, 3, tetCount, random)); // "Array 0x..."
  return mesh;
}
} // namespace

TEST(VtuWriter, SmallGridLikeVtk)
{
  ExpectVtkBytes(SyntheticGrid(10, 3));
}

TEST(VtuWriter, ManyBlocksLikeVtk)
{
  // 960000-byte points: 29 blocks and a partial one; integer arrays with ranges on threads.
  ExpectVtkBytes(SyntheticGrid(40000, 40000));
}

TEST(VtuWriter, WholeBlocksLikeVtk)
{
  ExpectVtkBytes(SyntheticGrid(4096, 2048)); // Float64 scalars, points, connectivity: whole blocks
}

TEST(VtuWriter, ThirtyTwoBitCellsLikeVtk)
{
  // The stages hand on 32-bit connectivity: written as Int32 arrays, as VTK writes them.
  auto mesh = SyntheticGrid(40000, 40000);
  ASSERT_TRUE(mesh->GetCells()->ConvertTo32BitStorage());
  ASSERT_FALSE(mesh->GetCells()->IsStorage64Bit());
  ExpectVtkBytes(mesh);
  EXPECT_NE(OurBytes(mesh, 1).find("<DataArray type=\"Int32\" Name=\"connectivity\""), std::string::npos);
}

TEST(VtuWriter, PointsWithoutCellsLikeVtk)
{
  ExpectVtkBytes(SyntheticGrid(20, 0));
}

TEST(VtuWriter, RandomDataLikeVtk)
{
  // Incompressible blocks: zlib's output is larger than its input.
  auto mesh = SyntheticGrid(3000, 100);
  std::mt19937_64 random(3);
  vtkNew<vtkDoubleArray> noise;
  noise->SetName("Noise");
  noise->SetNumberOfTuples(3000);
  for (vtkIdType i = 0; i < 3000; ++i)
    noise->SetValue(i, std::uniform_real_distribution<double>(-1e300, 1e300)(random));
  mesh->GetPointData()->AddArray(noise);
  ExpectVtkBytes(mesh);
}

TEST(VtuWriter, FallsBackOnTextArrays)
{
  auto mesh = SyntheticGrid(10, 3);
  vtkNew<vtkStringArray> words;
  words->SetName("Words");
  words->InsertNextValue("stop");
  mesh->GetFieldData()->AddArray(words);
  std::string bytes;
  EXPECT_FALSE(MakeVtuBytes(mesh, 1, bytes));
  EXPECT_TRUE(bytes.empty());
}

TEST(VtuWriter, FallsBackOnEmptyGrid)
{
  vtkNew<vtkUnstructuredGrid> mesh; // no points, no cell types: VTK's writer knows what to do
  std::string bytes;
  EXPECT_FALSE(MakeVtuBytes(mesh, 1, bytes));
}

// Each phantom meshed by cbc3d (on 1 and 2 threads, which must give the same file), read back:
// the file is VTK's writer's bytes for what it holds, and our writer writes the same.
TEST(VtuWriter, PhantomsLikeVtk)
{
  const std::string cli = CBC3D_CLI, source = CBC3D_SOURCE_DIR, output = CBC3D_TEST_OUTPUT;
  for (const char* phantom : { "ball", "nested_shells", "oblique_ball", "thin_tube", "touching_boxes" })
  {
    SCOPED_TRACE(phantom);
    std::string files[2];
    for (int threads : { 1, 2 })
    {
      const std::string path = output + "/vtu-" + phantom + "-" + std::to_string(threads) + ".vtu";
      const std::string command = "\"" + cli + "\" \"" + source + "/Data/" + phantom +
        ".vti\" -o \"" + path + "\" --quiet --threads " + std::to_string(threads) + " > /dev/null";
      ASSERT_EQ(std::system(command.c_str()), 0) << command;
      std::ifstream in(path, std::ios::binary);
      files[threads - 1].assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    EXPECT_TRUE(files[0] == files[1]) << "1 and 2 threads wrote different files";
    vtkNew<vtkXMLUnstructuredGridReader> reader;
    reader->SetFileName((output + "/vtu-" + phantom + "-1.vtu").c_str());
    reader->Update();
    ASSERT_GT(reader->GetOutput()->GetNumberOfCells(), 0);
    EXPECT_TRUE(VtkBytes(reader->GetOutput()) == files[0]) << "the file is not VTK's bytes";
    ExpectVtkBytes(reader->GetOutput());
  }
}
