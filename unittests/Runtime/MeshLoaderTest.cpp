//===--- MeshLoaderTest.cpp - TetGen, Gmsh and OBJ loaders ----------------===//

#include "simit/Runtime/Mesh.h"

#include "TestFiles.h"

#include "gmock/gmock.h"

using namespace simit;
using namespace simit::test;
using ::testing::HasSubstr;

namespace {

using Edge = std::array<int, 2>;
using Tri = std::array<int, 3>;
using Tet = std::array<int, 4>;

const char *kUnitNodes = "# four corners of the unit tet\n"
                         "4 3 0 0\n"
                         "0 0 0 0\n"
                         "1 1 0 0   # x axis\n"
                         "2 0 1 0\n"
                         "3 0 0 1\n";

//===--- TetGen -----------------------------------------------------------===//

TEST(TetGenLoader, ReadsNodesElementsEdgesAndFaces) {
  TempDir dir;
  dir.write("m.node", kUnitNodes);
  dir.write("m.ele", "1 4 0\n0 0 1 2 3\n");
  dir.write("m.edge", "2 1\n0 0 1 -1\n1 2 3 0\n");
  dir.write("m.face", "1 0\n0 1 2 3\n");
  auto mesh = loadTetGen(dir.path("m"));
  ASSERT_TRUE(bool(mesh)) << llvm::toString(mesh.takeError());
  ASSERT_EQ(mesh->points.size(), 4u);
  EXPECT_EQ(mesh->points[1], (std::array<double, 3>{1, 0, 0}));
  EXPECT_EQ(mesh->points[3], (std::array<double, 3>{0, 0, 1}));
  EXPECT_EQ(mesh->tets, (std::vector<Tet>{{0, 1, 2, 3}}));
  EXPECT_EQ(mesh->edges, (std::vector<Edge>{{0, 1}, {2, 3}}));
  EXPECT_EQ(mesh->triangles, (std::vector<Tri>{{1, 2, 3}}));
}

TEST(TetGenLoader, OneBasedFilesBecomeZeroBased) {
  TempDir dir;
  dir.write("m.node", "3 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n");
  dir.write("m.face", "1 0\n1 1 2 3\n");
  auto mesh = loadTetGen(dir.path("m"));
  ASSERT_TRUE(bool(mesh)) << llvm::toString(mesh.takeError());
  EXPECT_EQ(mesh->triangles, (std::vector<Tri>{{0, 1, 2}}));
  EXPECT_TRUE(mesh->tets.empty());
}

TEST(TetGenLoader, SkipsAttributesAndMarkers) {
  TempDir dir;
  dir.write("m.node", "4 3 2 1\n"
                      "0 0 0 0 7.5 8.5 1\n"
                      "1 1 0 0 7.5 8.5 0\n"
                      "2 0 1 0 7.5 8.5 0\n"
                      "3 0 0 1 7.5 8.5 1\n");
  dir.write("m.ele", "1 4 1\n0 3 2 1 0 42\n");
  auto mesh = loadTetGen(dir.path("m"));
  ASSERT_TRUE(bool(mesh)) << llvm::toString(mesh.takeError());
  EXPECT_EQ(mesh->points[2], (std::array<double, 3>{0, 1, 0}));
  EXPECT_EQ(mesh->tets, (std::vector<Tet>{{3, 2, 1, 0}}));
}

TEST(TetGenLoader, SecondOrderTetsKeepTheirCorners) {
  TempDir dir;
  dir.write("m.node", kUnitNodes);
  dir.write("m.ele", "1 10 0\n0 0 1 2 3 0 0 0 0 0 0\n");
  auto mesh = loadTetGen(dir.path("m"));
  ASSERT_TRUE(bool(mesh)) << llvm::toString(mesh.takeError());
  EXPECT_EQ(mesh->tets, (std::vector<Tet>{{0, 1, 2, 3}}));
}

TEST(TetGenLoader, TwoDimensionalNodesHaveZeroZ) {
  TempDir dir;
  dir.write("m.node", "2 2 0 0\n0 1.5 2.5\n1 3 4\n");
  auto mesh = loadTetGen(dir.path("m"));
  ASSERT_TRUE(bool(mesh)) << llvm::toString(mesh.takeError());
  EXPECT_EQ(mesh->points[0], (std::array<double, 3>{1.5, 2.5, 0}));
}

/// Loads <dir>/m with the given .node and .ele texts and returns the error.
std::string tetgenError(const TempDir &dir, llvm::StringRef node,
                        llvm::StringRef ele) {
  dir.write("m.node", node);
  if (!ele.empty())
    dir.write("m.ele", ele);
  return errorOf(loadTetGen(dir.path("m")));
}

TEST(TetGenLoader, MissingNodeFileIsAnError) {
  TempDir dir;
  std::string err = errorOf(loadTetGen(dir.path("absent")));
  EXPECT_THAT(err, HasSubstr("absent.node: cannot open"));
}

TEST(TetGenLoader, EmptyFileIsAnError) {
  TempDir dir;
  std::string err = tetgenError(dir, "# only a comment\n", "");
  EXPECT_THAT(err, HasSubstr("m.node:2: expected a header line"));
}

TEST(TetGenLoader, NonNumberCoordinateIsAnError) {
  TempDir dir;
  std::string err =
      tetgenError(dir, "2 3 0 0\n0 0 0 0\n1 0 zero 0\n", "");
  EXPECT_THAT(err, HasSubstr("m.node:3: expected a number for a coordinate, "
                             "found 'zero'"));
}

TEST(TetGenLoader, NonNumberHeaderIsAnError) {
  TempDir dir;
  std::string err = tetgenError(dir, "four 3 0 0\n", "");
  EXPECT_THAT(err, HasSubstr("m.node:1: expected an integer for header "
                             "field 1"));
}

TEST(TetGenLoader, TruncatedNodeFileIsAnError) {
  TempDir dir;
  std::string err = tetgenError(dir, "3 3 0 0\n0 0 0 0\n1 1 0 0\n", "");
  EXPECT_THAT(err, HasSubstr("m.node:4: expected point 3 of 3, found the "
                             "end of the file"));
}

TEST(TetGenLoader, ExtraRecordsAreAnError) {
  TempDir dir;
  std::string err = tetgenError(dir, "1 3 0 0\n0 0 0 0\n1 1 0 0\n", "");
  EXPECT_THAT(err, HasSubstr("m.node:3: expected the end of the file after "
                             "1 points"));
}

TEST(TetGenLoader, WrongColumnCountIsAnError) {
  TempDir dir;
  std::string err = tetgenError(dir, "1 3 1 0\n0 0 0 0\n", "");
  EXPECT_THAT(err, HasSubstr("m.node:2: expected 5 values"));
}

TEST(TetGenLoader, DuplicatedIndexIsAnError) {
  TempDir dir;
  std::string err =
      tetgenError(dir, "3 3 0 0\n0 0 0 0\n1 1 0 0\n1 0 1 0\n", "");
  EXPECT_THAT(err, HasSubstr("m.node:4: duplicated record index 1"));
}

TEST(TetGenLoader, SkippedIndexIsAnError) {
  TempDir dir;
  std::string err = tetgenError(dir, "2 3 0 0\n0 0 0 0\n2 1 0 0\n", "");
  EXPECT_THAT(err, HasSubstr("m.node:3: expected record index 1, found 2"));
}

TEST(TetGenLoader, FirstIndexMustBeZeroOrOne) {
  TempDir dir;
  std::string err = tetgenError(dir, "1 3 0 0\n5 0 0 0\n", "");
  EXPECT_THAT(err, HasSubstr("m.node:2: expected the first record index to "
                             "be 0 or 1, found 5"));
}

TEST(TetGenLoader, OutOfRangeVertexIsAnError) {
  TempDir dir;
  std::string err = tetgenError(dir, kUnitNodes, "1 4 0\n0 0 1 2 4\n");
  EXPECT_THAT(err, HasSubstr("m.ele:2: vertex index 4 is out of range "
                             "(0..3)"));
}

TEST(TetGenLoader, OneBasedVertexZeroIsOutOfRange) {
  TempDir dir;
  std::string err = tetgenError(
      dir, "4 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n",
      "1 4 0\n1 0 1 2 3\n");
  EXPECT_THAT(err, HasSubstr("m.ele:2: vertex index 0 is out of range "
                             "(1..4)"));
}

TEST(TetGenLoader, WrongNodesPerTetIsAnError) {
  TempDir dir;
  std::string err = tetgenError(dir, kUnitNodes, "1 5 0\n0 0 1 2 3 0\n");
  EXPECT_THAT(err, HasSubstr("m.ele:1: expected 4 or 10 nodes per "
                             "tetrahedron, found 5"));
}

TEST(TetGenLoader, TruncatedElementFileIsAnError) {
  TempDir dir;
  std::string err = tetgenError(dir, kUnitNodes, "2 4 0\n0 0 1 2 3\n");
  EXPECT_THAT(err, HasSubstr("m.ele:3: expected tetrahedron 2 of 2"));
}

TEST(TetGenLoader, BadEdgeFileIsAnError) {
  TempDir dir;
  dir.write("m.node", kUnitNodes);
  dir.write("m.edge", "1 0\n0 1\n");
  std::string err = errorOf(loadTetGen(dir.path("m")));
  EXPECT_THAT(err, HasSubstr("m.edge:2: expected 3 values"));
  dir.write("m.edge", "1 0\n0 1 x 2\n");
  err = errorOf(loadTetGen(dir.path("m")));
  EXPECT_THAT(err, HasSubstr("m.edge:2: expected 3 values"));
  dir.write("m.edge", "1 1\n0 1 x 2\n");
  err = errorOf(loadTetGen(dir.path("m")));
  EXPECT_THAT(err, HasSubstr("m.edge:2: expected an integer for a vertex "
                             "index, found 'x'"));
}

TEST(TetGenLoader, OneBasedTetsBecomeZeroBased) {
  TempDir dir;
  dir.write("m.node", "4 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n");
  dir.write("m.ele", "1 4 0\n1 4 3 2 1\n");
  auto mesh = loadTetGen(dir.path("m"));
  ASSERT_TRUE(bool(mesh)) << llvm::toString(mesh.takeError());
  EXPECT_EQ(mesh->tets, (std::vector<Tet>{{3, 2, 1, 0}}));
}

TEST(TetGenLoader, ElementFilesFollowTheNumberingOfTheNodeFile) {
  TempDir dir;
  // 1-based points, 0-based tets: vertex 0 would silently shift by one.
  std::string err = tetgenError(
      dir, "4 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n",
      "1 4 0\n0 1 2 3 4\n");
  EXPECT_THAT(err, HasSubstr("m.ele:2: expected the first record index to "
                             "be 1, the numbering of the .node file, found "
                             "0"));
}

TEST(TetGenLoader, TwoDimensionalNodesCannotHoldTets) {
  TempDir dir;
  std::string err = tetgenError(dir, "4 2 0 0\n0 0 0\n1 1 0\n2 0 1\n3 1 1\n",
                                "1 4 0\n0 0 1 2 3\n");
  EXPECT_THAT(err, HasSubstr("m.node: expected 3-D points for the "
                             "tetrahedra of "));
  EXPECT_THAT(err, HasSubstr("found dimension 2"));
}

TEST(TetGenLoader, NonFiniteCoordinateIsAnError) {
  TempDir dir;
  for (const char *value : {"nan", "inf", "-inf", "1e999"}) {
    std::string node = "2 3 0 0\n0 0 0 0\n1 0 " + std::string(value) + " 0\n";
    EXPECT_THAT(tetgenError(dir, node, ""),
                HasSubstr("m.node:3: expected a finite number for a "
                          "coordinate, found '" +
                          std::string(value) + "'"));
  }
}

TEST(TetGenLoader, CountsBeyondTheFileReserveOnlyWhatTheFileHolds) {
  TempDir dir;
  // 2e9 points would take 48 GB; the file holds one.
  std::string err = tetgenError(dir, "2000000000 3 0 0\n0 0 0 0\n", "");
  EXPECT_THAT(err, HasSubstr("m.node:3: expected point 2 of 2000000000, "
                             "found the end of the file"));
  err = tetgenError(dir, kUnitNodes, "2000000000 4 0\n0 0 1 2 3\n");
  EXPECT_THAT(err, HasSubstr("m.ele:3: expected tetrahedron 2 of "
                             "2000000000, found the end of the file"));
}

TEST(TetGenLoader, NegativeHeaderCountIsAnError) {
  TempDir dir;
  std::string err = tetgenError(dir, "-1 3 0 0\n", "");
  EXPECT_THAT(err, HasSubstr("m.node:1: expected a non-negative header"));
}

//===--- Gmsh -------------------------------------------------------------===//

const char *kGmsh2 = R"($MeshFormat
2.2 0 8
$EndMeshFormat
$PhysicalNames
1
3 1 "body #1"
$EndPhysicalNames
$Nodes
5
10 0 0 0
20 1 0 0
30 0 1 0
40 0 0 1
50 1 1 1
$EndNodes
$Elements
5
1 15 2 0 10 10
2 1 2 0 1 10 20
3 2 2 0 1 20 30 40
4 4 2 1 1 10 20 30 40
5 3 2 0 1 10 20 50 30
$EndElements
)";

TEST(GmshLoader, ReadsVersion2) {
  TempDir dir;
  auto mesh = loadGmsh(dir.write("m.msh", kGmsh2));
  ASSERT_TRUE(bool(mesh)) << llvm::toString(mesh.takeError());
  ASSERT_EQ(mesh->points.size(), 5u);
  EXPECT_EQ(mesh->points[4], (std::array<double, 3>{1, 1, 1}));
  EXPECT_EQ(mesh->edges, (std::vector<Edge>{{0, 1}}));
  EXPECT_EQ(mesh->triangles, (std::vector<Tri>{{1, 2, 3}}));
  // The quadrangle (type 3) is not part of the mesh model.
  EXPECT_EQ(mesh->tets, (std::vector<Tet>{{0, 1, 2, 3}}));
}

const char *kGmsh41 = R"($MeshFormat
4.1 0 8
$EndMeshFormat
$Entities
0 0 0 1
1 0 0 0 1 1 1 0 0
$EndEntities
$Nodes
2 4 1 4
3 1 0 3
1
2
3
0 0 0
1 0 0
0 1 0
2 1 0 1
4
0 0 1
$EndNodes
$Elements
2 2 1 2
2 1 2 1
1 1 2 3
3 1 4 1
2 1 2 3 4
$EndElements
)";

TEST(GmshLoader, ReadsVersion41) {
  TempDir dir;
  auto mesh = loadGmsh(dir.write("m.msh", kGmsh41));
  ASSERT_TRUE(bool(mesh)) << llvm::toString(mesh.takeError());
  ASSERT_EQ(mesh->points.size(), 4u);
  EXPECT_EQ(mesh->points[3], (std::array<double, 3>{0, 0, 1}));
  EXPECT_EQ(mesh->triangles, (std::vector<Tri>{{0, 1, 2}}));
  EXPECT_EQ(mesh->tets, (std::vector<Tet>{{0, 1, 2, 3}}));
}

TEST(GmshLoader, ReadsVersion40) {
  TempDir dir;
  const char *text = R"($MeshFormat
4 0 8
$EndMeshFormat
$Nodes
1 4
1 3 0 4
7 0 0 0
8 1 0 0
9 0 1 0
6 0 0 1
$EndNodes
$Elements
1 1
1 3 4 1
1 6 7 8 9
$EndElements
)";
  auto mesh = loadGmsh(dir.write("m.msh", text));
  ASSERT_TRUE(bool(mesh)) << llvm::toString(mesh.takeError());
  EXPECT_EQ(mesh->tets, (std::vector<Tet>{{3, 0, 1, 2}}));
}

TEST(GmshLoader, UnknownNodeTagIsAnError) {
  TempDir dir;
  std::string text = kGmsh2;
  text.replace(text.find("4 4 2 1 1 10 20 30 40"), 21,
               "4 4 2 1 1 10 20 30 99");
  std::string err = errorOf(loadGmsh(dir.write("m.msh", text)));
  EXPECT_THAT(err, HasSubstr("m.msh:21: unknown node tag 99"));
}

TEST(GmshLoader, BinaryFilesAreRejected) {
  TempDir dir;
  std::string err = errorOf(
      loadGmsh(dir.write("m.msh", "$MeshFormat\n2.2 1 8\n$EndMeshFormat\n")));
  EXPECT_THAT(err, HasSubstr("m.msh:2: expected an ASCII file"));
}

TEST(GmshLoader, UnsupportedVersionIsAnError) {
  TempDir dir;
  std::string err = errorOf(
      loadGmsh(dir.write("m.msh", "$MeshFormat\n3.0 0 8\n$EndMeshFormat\n")));
  EXPECT_THAT(err, HasSubstr("m.msh:2: expected format version 2.x or 4.x"));
}

TEST(GmshLoader, TruncatedFileIsAnError) {
  TempDir dir;
  std::string text = kGmsh2;
  text.resize(text.find("40 0 0 1"));
  std::string err = errorOf(loadGmsh(dir.write("m.msh", text)));
  EXPECT_THAT(err, HasSubstr("m.msh:13: expected node 4 of 5, found the end "
                             "of the file"));
}

TEST(GmshLoader, WrongElementArityIsAnError) {
  TempDir dir;
  std::string text = kGmsh2;
  text.replace(text.find("3 2 2 0 1 20 30 40"), 18, "3 2 2 0 1 20 30 ");
  std::string err = errorOf(loadGmsh(dir.write("m.msh", text)));
  EXPECT_THAT(err, HasSubstr("m.msh:20: expected 3 node tags for element "
                             "type 2, found 2"));
}

TEST(GmshLoader, DuplicatedNodeTagIsAnError) {
  TempDir dir;
  std::string text = kGmsh2;
  text.replace(text.find("50 1 1 1"), 8, "40 1 1 1");
  std::string err = errorOf(loadGmsh(dir.write("m.msh", text)));
  EXPECT_THAT(err, HasSubstr("m.msh:14: duplicated node tag 40"));
}

TEST(GmshLoader, MissingFormatSectionIsAnError) {
  TempDir dir;
  std::string err =
      errorOf(loadGmsh(dir.write("m.msh", "$Nodes\n0\n$EndNodes\n")));
  EXPECT_THAT(err, HasSubstr("m.msh:1: expected $MeshFormat before $Nodes"));
}

TEST(GmshLoader, ElementsBeforeNodesIsAnError) {
  TempDir dir;
  std::string err = errorOf(loadGmsh(dir.write(
      "m.msh", "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Elements\n0\n"
               "$EndElements\n")));
  EXPECT_THAT(err, HasSubstr("m.msh:4: expected $Nodes before $Elements"));
}

TEST(GmshLoader, MissingSectionEndIsAnError) {
  TempDir dir;
  std::string err = errorOf(loadGmsh(dir.write(
      "m.msh", "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n1\n"
               "1 0 0 0\n$Elements\n")));
  EXPECT_THAT(err, HasSubstr("m.msh:7: expected $EndNodes, found "
                             "'$Elements'"));
}

TEST(GmshLoader, NonNumberCoordinateIsAnError) {
  TempDir dir;
  std::string text = kGmsh2;
  text.replace(text.find("20 1 0 0"), 8, "20 1 O 0");
  std::string err = errorOf(loadGmsh(dir.write("m.msh", text)));
  EXPECT_THAT(err, HasSubstr("m.msh:11: expected a number for a coordinate, "
                             "found 'O'"));
}

TEST(GmshLoader, NonFiniteCoordinateIsAnError) {
  TempDir dir;
  std::string text = kGmsh2;
  text.replace(text.find("20 1 0 0"), 8, "20 1 nan 0");
  std::string err = errorOf(loadGmsh(dir.write("m.msh", text)));
  EXPECT_THAT(err, HasSubstr("m.msh:11: expected a finite number for a "
                             "coordinate, found 'nan'"));
}

TEST(GmshLoader, CountsBeyondTheFileReserveOnlyWhatTheFileHolds) {
  TempDir dir;
  std::string err = errorOf(loadGmsh(dir.write(
      "m.msh", "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n"
               "2000000000\n1 0 0 0\n")));
  EXPECT_THAT(err, HasSubstr("m.msh:7: expected node 2 of 2000000000, found "
                             "the end of the file"));
  // Format 4.1 reads a block's tags into an array before its coordinates.
  err = errorOf(loadGmsh(dir.write(
      "m4.msh", "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n"
                "1 2000000000 1 2000000000\n3 1 0 2000000000\n1\n")));
  EXPECT_THAT(err, HasSubstr("m4.msh:8: expected a node tag, found the end "
                             "of the file"));
}

//===--- OBJ --------------------------------------------------------------===//

TEST(ObjLoader, FanTriangulatesPolygonsAndResolvesNegativeIndices) {
  TempDir dir;
  const char *text = "# a square and a triangle\n"
                     "o square\n"
                     "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                     "vn 0 0 1\nvt 0 0\n"
                     "f 1/1/1 2/1/1 3//1 4\n"
                     "v 2 2 2 1.0\n"
                     "f -1 -4 -3\n";
  auto mesh = loadObj(dir.write("m.obj", text));
  ASSERT_TRUE(bool(mesh)) << llvm::toString(mesh.takeError());
  ASSERT_EQ(mesh->points.size(), 5u);
  EXPECT_EQ(mesh->triangles,
            (std::vector<Tri>{{0, 1, 2}, {0, 2, 3}, {4, 1, 2}}));
}

TEST(ObjLoader, OutOfRangeIndexIsAnError) {
  TempDir dir;
  std::string err =
      errorOf(loadObj(dir.write("m.obj", "v 0 0 0\nv 1 0 0\nf 1 2 3\n")));
  EXPECT_THAT(err, HasSubstr("m.obj:3: vertex index 3 is out of range"));
  err = errorOf(loadObj(dir.write("m.obj", "v 0 0 0\nf 1 -2 0\n")));
  EXPECT_THAT(err, HasSubstr("m.obj:2: vertex index -2 is out of range"));
}

TEST(ObjLoader, MalformedRecordsAreErrors) {
  TempDir dir;
  EXPECT_THAT(errorOf(loadObj(dir.write("m.obj", "v 0 0\n"))),
              HasSubstr("m.obj:1: expected 'v x y z [w]'"));
  EXPECT_THAT(errorOf(loadObj(dir.write("m.obj", "v 0 0 0\nf 1 1\n"))),
              HasSubstr("m.obj:2: expected a face of at least 3 vertices"));
  EXPECT_THAT(errorOf(loadObj(dir.write("m.obj", "v 0 0 a\n"))),
              HasSubstr("m.obj:1: expected a number for a coordinate"));
  EXPECT_THAT(errorOf(loadObj(dir.write("m.obj", "v 0 inf 0\n"))),
              HasSubstr("m.obj:1: expected a finite number for a "
                        "coordinate, found 'inf'"));
}

//===--- Dispatch ---------------------------------------------------------===//

TEST(MeshDispatch, ChoosesTheLoaderByExtension) {
  TempDir dir;
  dir.write("m.node", kUnitNodes);
  dir.write("m.ele", "1 4 0\n0 0 1 2 3\n");
  for (const char *name : {"m.node", "m.ele", "m"}) {
    auto mesh = loadMesh(dir.path(name));
    ASSERT_TRUE(bool(mesh)) << name << ": " << llvm::toString(mesh.takeError());
    EXPECT_EQ(mesh->tets.size(), 1u) << name;
  }
  auto gmsh = loadMesh(dir.write("g.MSH", kGmsh2));
  ASSERT_TRUE(bool(gmsh)) << llvm::toString(gmsh.takeError());
  EXPECT_EQ(gmsh->points.size(), 5u);
  auto obj = loadMesh(dir.write("o.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
  ASSERT_TRUE(bool(obj)) << llvm::toString(obj.takeError());
  EXPECT_EQ(obj->triangles.size(), 1u);
  EXPECT_THAT(errorOf(loadMesh(dir.write("x.stl", ""))),
              HasSubstr("x.stl: unknown mesh format '.stl'"));
}

} // namespace
