// The solver-format writers on two unit cubes of tissues 1 and 2 (12 points, 12 tets, 22
// triangles: boundary_1 and boundary_2 of 10, interface_1_2 of 2): counts, names, and the
// Abaqus faces, read back from the text.
#include "TestMeshes.h"
#include "TestTaggedMeshes.h"

#include "cbc3d/export/MeshExport.h"

#include <gtest/gtest.h>

#include <map>
#include <sstream>

namespace
{
using namespace cbc3d;

std::string Export(const TaggedMesh& mesh, const std::string& extension, bool gmsh22 = false)
{
  std::ostringstream out;
  const Status status = WriteExport(mesh, extension, out, gmsh22);
  EXPECT_TRUE(status.IsOk()) << status.GetMessage();
  return out.str();
}

std::size_t Count(const std::string& text, const std::string& word)
{
  std::size_t n = 0;
  for (std::size_t at = text.find(word); at != std::string::npos; at = text.find(word, at + 1))
    ++n;
  return n;
}

bool Has(const std::string& text, const std::string& part)
{
  return text.find(part) != std::string::npos;
}

TEST(MeshExport, GmshNamesEveryTissueAndSurface)
{
  const TaggedMesh mesh = cbc3d::testing::TwoTaggedCubes();
  const std::string names = "$PhysicalNames\n5\n2 1 \"boundary_1\"\n2 2 \"boundary_2\"\n"
                            "2 3 \"interface_1_2\"\n3 1 \"tissue_1\"\n3 2 \"tissue_2\"\n";
  const std::string v41 = Export(mesh, ".msh");
  EXPECT_TRUE(Has(v41, "$MeshFormat\n4.1 0 8\n"));
  EXPECT_TRUE(Has(v41, names));
  EXPECT_TRUE(Has(v41, "$Entities\n0 0 3 2\n"));
  EXPECT_TRUE(Has(v41, "$Nodes\n1 12 1 12\n"));
  EXPECT_TRUE(Has(v41, "$Elements\n5 34 1 34\n2 1 2 10\n"));
  EXPECT_TRUE(Has(v41, "\n2 3 2 2\n")); // the interface: 2 triangles
  EXPECT_TRUE(Has(v41, "\n3 2 4 6\n")); // tissue 2: 6 tets
  const std::string v22 = Export(mesh, ".msh", true);
  EXPECT_TRUE(Has(v22, "$MeshFormat\n2.2 0 8\n"));
  EXPECT_TRUE(Has(v22, names));
  EXPECT_TRUE(Has(v22, "$Nodes\n12\n"));
  EXPECT_TRUE(Has(v22, "$Elements\n34\n"));
  EXPECT_EQ(Count(v22, " 2 2 3 3 "), 2u);  // triangles tagged interface_1_2
  EXPECT_EQ(Count(v22, " 4 2 2 2 "), 6u);  // tets tagged tissue_2
}

TEST(MeshExport, GmshRejectsTissueLabelZero)
{
  TaggedMesh mesh = cbc3d::testing::TwoTaggedCubes();
  mesh.Tissues.front() = 0;
  std::ostringstream out;
  EXPECT_FALSE(WriteExport(mesh, ".msh", out).IsOk());
}

TEST(MeshExport, LabelsBeyond32BitsAreNamedOrRefused)
{
  // Codes 0, 1, 2 stand for -1 (the outside), 5000000000 and 6000000000.
  const TaggedMesh mesh =
    cbc3d::testing::TwoTaggedCubes(LabelCodes::ForValues({ -1, 5000000000, 6000000000 }));
  EXPECT_EQ(mesh.Surfaces[2].Name, "interface_5000000000_6000000000");
  const std::string abaqus = Export(mesh, ".inp");
  EXPECT_TRUE(Has(abaqus, "*ELSET, ELSET=tissue_6000000000\n"));
  EXPECT_TRUE(Has(abaqus, "boundary_5000000000"));
  EXPECT_TRUE(Has(Export(mesh, ".feb"), "<SolidDomain name=\"tissue_5000000000\" mat=\"tissue_5000000000\"/>"));
  for (const char* extension : { ".msh", ".mesh" })
  {
    std::ostringstream out;
    const Status status = WriteExport(mesh, extension, out);
    EXPECT_TRUE(Has(status.GetMessage(), "cannot hold tissue label 5000000000")) << status.GetMessage();
  }
}

TEST(MeshExport, SmallTissuesWithALargeOutsideWriteTheirValues)
{
  // Codes 1 and 2 stand for 1 and 2, code 3 (the outside) for 5000000000.
  const TaggedMesh mesh =
    cbc3d::testing::TwoTaggedCubes(LabelCodes::ForValues({ 0, 1, 2, 5000000000 }), 3);
  EXPECT_TRUE(Has(Export(mesh, ".msh"), "3 1 \"tissue_1\"\n3 2 \"tissue_2\"\n"));
  const std::string medit = Export(mesh, ".mesh");
  EXPECT_EQ(Count(medit.substr(medit.find("\nTetrahedra\n")), " 2\n"), 6u); // tissue 2's tets, ref 2
}

TEST(MeshExport, MeditRefsAreLabelsAndSurfaceIds)
{
  const std::string text = Export(cbc3d::testing::TwoTaggedCubes(), ".mesh");
  EXPECT_TRUE(Has(text, "Triangles\n22\n"));
  EXPECT_TRUE(Has(text, "Tetrahedra\n12\n"));
  EXPECT_TRUE(Has(text, "# 3 interface_1_2\n"));
  EXPECT_EQ(Count(text, " 3\n"), 3u); // "Dimension 3" and the two interface triangles
}

TEST(MeshExport, FEBioHasABlockPerTissueAndASurfacePerPair)
{
  const std::string text = Export(cbc3d::testing::TwoTaggedCubes(), ".feb");
  EXPECT_TRUE(Has(text, "<febio_spec version=\"4.0\">"));
  EXPECT_EQ(Count(text, "<node id="), 12u);
  EXPECT_EQ(Count(text, "<elem id="), 12u);
  EXPECT_EQ(Count(text, "<Elements type=\"tet4\""), 2u);
  EXPECT_EQ(Count(text, "<tri3 id="), 22u);
  EXPECT_TRUE(Has(text, "<Surface name=\"interface_1_2\">"));
  EXPECT_TRUE(Has(text, "<SolidDomain name=\"tissue_2\" mat=\"tissue_2\"/>"));
  EXPECT_EQ(Count(text, "<material id="), 2u);
}

// Reads the Abaqus element sets and surfaces back: surface name -> (element, face) pairs.
std::map<std::string, std::vector<std::pair<int, int>>> AbaqusSurfaces(const std::string& text)
{
  std::map<std::string, std::vector<int>> sets;
  std::map<std::string, std::vector<std::pair<int, int>>> surfaces;
  std::istringstream in(text);
  std::string line, set, surface;
  while (std::getline(in, line))
  {
    if (line.rfind("*ELSET, ELSET=", 0) == 0)
      set = line.substr(14), surface.clear();
    else if (line.rfind("*SURFACE, TYPE=ELEMENT, NAME=", 0) == 0)
      surface = line.substr(29), set.clear();
    else if (line[0] == '*')
      set.clear(), surface.clear();
    else if (!surface.empty())
    {
      const std::size_t comma = line.find(", S");
      for (const int element : sets[line.substr(0, comma)])
        surfaces[surface].emplace_back(element, std::stoi(line.substr(comma + 3)));
    }
    else if (!set.empty())
    {
      std::istringstream ids(line);
      for (std::string id; std::getline(ids, id, ',');)
        sets[set].push_back(std::stoi(id));
    }
  }
  return surfaces;
}

TEST(MeshExport, AbaqusSurfacesAreTheRightTetFaces)
{
  const TaggedMesh mesh = cbc3d::testing::TwoTaggedCubes();
  const std::string text = Export(mesh, ".inp");
  EXPECT_EQ(Count(text, "*ELSET, ELSET=tissue_"), 2u);
  EXPECT_EQ(Count(text, "*SURFACE, TYPE=ELEMENT"), 3u);
  const auto surfaces = AbaqusSurfaces(text);
  ASSERT_EQ(surfaces.at("interface_1_2").size(), 2u);
  ASSERT_EQ(surfaces.at("boundary_1").size(), 10u);
  // C3D4 faces by their 1-based nodes: S1 1-2-3, S2 1-4-2, S3 2-4-3, S4 3-4-1.
  const int faceNodes[5][3] = { {}, { 0, 1, 2 }, { 0, 3, 1 }, { 1, 3, 2 }, { 2, 3, 0 } };
  for (const auto& [element, face] : surfaces.at("interface_1_2"))
  {
    EXPECT_EQ(mesh.Labels[element - 1], 1); // on tissue 1's tets
    for (const int k : faceNodes[face])
      EXPECT_EQ(mesh.Points[mesh.Tets[element - 1][k]].x(), 1.0); // on the plane x = 1
  }
  for (const auto& [element, face] : surfaces.at("boundary_1"))
  {
    double lowest = 1.0;
    for (const int k : faceNodes[face])
      lowest = std::min(lowest, mesh.Points[mesh.Tets[element - 1][k]].x());
    EXPECT_EQ(mesh.Labels[element - 1], 1);
    EXPECT_EQ(lowest, 0.0); // no boundary face of cube 1 lies wholly on x = 1
  }
}

TEST(MeshExport, UnknownExtensionAndEmptyMeshFail)
{
  std::ostringstream out;
  EXPECT_FALSE(WriteExport(cbc3d::testing::TwoTaggedCubes(), ".stl", out).IsOk());
  EXPECT_FALSE(IsExportExtension(".vtu"));
  EXPECT_TRUE(IsExportExtension(".feb"));
  for (const std::string extension : { ".msh", ".inp", ".mesh", ".feb", ".xdmf" })
    EXPECT_FALSE(WriteExport(TaggedMesh(), extension, out).IsOk()) << extension;
}
} // namespace
