//===--- OutputTest.cpp - VTK, CSV and per-frame scene outputs ------------===//

#include "simit/Runtime/CSV.h"
#include "simit/Runtime/SceneOutput.h"
#include "simit/Runtime/VTK.h"

#include "TestFiles.h"

#include "gmock/gmock.h"

#include "llvm/Support/FileSystem.h"
#include "llvm/Support/MemoryBuffer.h"
#include "llvm/Support/Path.h"

#include <algorithm>
#include <csignal>
#include <sstream>
#include <sys/resource.h>

using namespace simit;
using namespace simit::test;
using ::testing::HasSubstr;

namespace {

/// The numbers inside the <DataArray> whose opening tag contains `tag`, or
/// inside the element `tag` (such as "<Points>").
std::vector<double> dataArray(const std::string &xml, const std::string &tag) {
  size_t at = xml.find(tag);
  if (at == std::string::npos) {
    ADD_FAILURE() << "no DataArray with " << tag;
    return {};
  }
  // A tag around the array (<Points>) leads to the DataArray inside it.
  if (tag.find("DataArray") == std::string::npos && tag[0] == '<')
    at = xml.find("<DataArray", at);
  size_t begin = xml.find('>', at) + 1;
  size_t end = xml.find("</DataArray>", begin);
  std::istringstream in(xml.substr(begin, end - begin));
  std::vector<double> values;
  for (double v; in >> v;)
    values.push_back(v);
  return values;
}

std::string readFile(const std::string &path) {
  auto buffer = llvm::MemoryBuffer::getFile(path);
  if (!buffer) {
    ADD_FAILURE() << path << ": " << buffer.getError().message();
    return "";
  }
  return (*buffer)->getBuffer().str();
}

/// Three points, a tet over four (one repeated would be degenerate, so use
/// four points), two springs and a triangle.
struct SmallMesh {
  Set points{"points"};
  Set tets{"tets", {&points, &points, &points, &points}};
  Set springs{"springs", {&points, &points}};
  Set faces{"faces", {&points, &points, &points}};

  SmallMesh() {
    auto x = points.addField<double, 3>("x");
    auto temperature = points.addField<float>("T");
    auto fixed = points.addField<bool>("fixed");
    auto volume = tets.addField<double>("W");
    for (int i = 0; i < 4; ++i) {
      points.add();
      x.set(i, {double(i == 1), double(i == 2), double(i == 3) + 0.125});
      temperature.set(i, 20.5f + i);
      fixed.set(i, i == 0);
    }
    volume.set(tets.add(0, 1, 2, 3), 1.0 / 6);
    springs.add(0, 1);
    springs.add(2, 3);
    faces.add(1, 2, 3);
  }
};

TEST(VTK, CellTypes) {
  EXPECT_EQ(vtkCellType(1), 1);
  EXPECT_EQ(vtkCellType(2), 3);
  EXPECT_EQ(vtkCellType(3), 5);
  EXPECT_EQ(vtkCellType(4), 10);
  EXPECT_EQ(vtkCellType(5), -1);
}

TEST(VTK, WritesPointsCellsAndData) {
  SmallMesh mesh;
  VTKOptions options;
  options.cellSets = {&mesh.tets, &mesh.springs, &mesh.faces};
  options.pointFields = {"T", "fixed"};
  std::string xml;
  llvm::raw_string_ostream os(xml);
  ASSERT_FALSE(bool(writeVTU(os, mesh.points, options)));
  os.flush();
  EXPECT_THAT(xml, HasSubstr("<VTKFile type=\"UnstructuredGrid\""));
  EXPECT_THAT(xml, HasSubstr("<Piece NumberOfPoints=\"4\" "
                             "NumberOfCells=\"4\">"));
  EXPECT_EQ(dataArray(xml, "<Points>"),
            (std::vector<double>{0, 0, 0.125, 1, 0, 0.125, 0, 1, 0.125, 0, 0,
                                 1.125}));
  EXPECT_EQ(dataArray(xml, "Name=\"connectivity\""),
            (std::vector<double>{0, 1, 2, 3, 0, 1, 2, 3, 1, 2, 3}));
  EXPECT_EQ(dataArray(xml, "Name=\"offsets\""),
            (std::vector<double>{4, 6, 8, 11}));
  EXPECT_EQ(dataArray(xml, "Name=\"types\""),
            (std::vector<double>{10, 3, 3, 5}));
  EXPECT_THAT(xml, HasSubstr("type=\"Float32\" Name=\"T\" "
                             "NumberOfComponents=\"1\""));
  EXPECT_EQ(dataArray(xml, "Name=\"T\""),
            (std::vector<double>{20.5, 21.5, 22.5, 23.5}));
  EXPECT_THAT(xml, HasSubstr("type=\"UInt8\" Name=\"fixed\""));
  EXPECT_EQ(dataArray(xml, "Name=\"fixed\""),
            (std::vector<double>{1, 0, 0, 0}));
  EXPECT_THAT(xml, HasSubstr("</VTKFile>\n"));
}

TEST(VTK, CellFieldsAndFullPrecision) {
  SmallMesh mesh;
  VTKOptions options;
  options.cellSets = {&mesh.tets};
  options.cellFields = {"W"};
  std::string xml;
  llvm::raw_string_ostream os(xml);
  ASSERT_FALSE(bool(writeVTU(os, mesh.points, options)));
  os.flush();
  std::vector<double> w = dataArray(xml, "Name=\"W\"");
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(w[0], 1.0 / 6) << "17 significant digits read back exactly";
}

TEST(VTK, OptionErrors) {
  SmallMesh mesh;
  VTKOptions options;
  options.positionField = "y";
  EXPECT_THAT(errorOf(checkVTKOptions(mesh.points, options)),
              HasSubstr("VTK output of set 'points': no position field 'y'"));
  options.positionField = "T";
  EXPECT_THAT(errorOf(checkVTKOptions(mesh.points, options)),
              HasSubstr("the position field 'T' is not a float vector of 3"));
  options = VTKOptions();
  options.pointFields = {"v"};
  EXPECT_THAT(errorOf(checkVTKOptions(mesh.points, options)),
              HasSubstr("no point field 'v'"));
  options = VTKOptions();
  Set other("other");
  Set links("links", {&mesh.points, &other});
  options.cellSets = {&links};
  EXPECT_THAT(errorOf(checkVTKOptions(mesh.points, options)),
              HasSubstr("set 'links' is not an edge set over it"));
  options = VTKOptions();
  options.cellSets = {&mesh.tets, &mesh.springs};
  options.cellFields = {"W"};
  EXPECT_THAT(errorOf(checkVTKOptions(mesh.points, options)),
              HasSubstr("cell fields need exactly one cell set"));
  options.cellSets = {&mesh.springs};
  EXPECT_THAT(errorOf(checkVTKOptions(mesh.points, options)),
              HasSubstr("no cell field 'W' on set 'springs'"));
  TempDir dir;
  options = VTKOptions();
  EXPECT_THAT(errorOf(writeVTU(dir.path("missing/dir/a.vtu"), mesh.points,
                               options)),
              HasSubstr("a.vtu: cannot write"));
}

TEST(CSV, HeaderAndRows) {
  Set set("s");
  auto b = set.addField<double, 2, 2>("B");
  auto n = set.addField<int32_t>("n");
  set.add();
  set.add();
  b.set(1, {1.0 / 3, 2, 3, 4});
  n.set(1, -7);
  EXPECT_EQ(csvHeader(set, {"n", "B"}, true),
            "frame,element,n,B_0_0,B_0_1,B_1_0,B_1_1\n");
  std::string text;
  llvm::raw_string_ostream os(text);
  ASSERT_FALSE(bool(writeCSVRows(os, set, {"n", "B"}, 5)));
  os.flush();
  EXPECT_EQ(text, "5,0,0,0,0,0,0\n"
                  "5,1,-7,0.33333333333333331,2,3,4\n");
  EXPECT_EQ(std::stod("0.33333333333333331"), 1.0 / 3);
}

TEST(CSV, WholeFileAndErrors) {
  Set set("s");
  auto x = set.addField<double, 3>("x");
  x.set(set.add(), {1, 2, 3});
  TempDir dir;
  ASSERT_FALSE(bool(writeCSV(dir.path("x.csv"), set, {"x"})));
  EXPECT_EQ(readFile(dir.path("x.csv")), "element,x_0,x_1,x_2\n0,1,2,3\n");
  EXPECT_THAT(errorOf(writeCSV(dir.path("y.csv"), set, {"y"})),
              HasSubstr("CSV output of set 's': no field 'y'"));
  EXPECT_THAT(errorOf(writeCSV(dir.path("no/such/dir.csv"), set, {"x"})),
              HasSubstr("dir.csv: cannot write"));
}

/// Limits the size of files the process writes (`ulimit -f`), a disk
/// that fills up after `bytes`, for the test's duration: writes past it
/// fail with EFBIG instead of raising SIGXFSZ.
class FileSizeLimit {
public:
  explicit FileSizeLimit(rlim_t bytes) {
    savedHandler = std::signal(SIGXFSZ, SIG_IGN);
    getrlimit(RLIMIT_FSIZE, &saved);
    struct rlimit lower = saved;
    lower.rlim_cur = bytes;
    setrlimit(RLIMIT_FSIZE, &lower);
  }
  ~FileSizeLimit() {
    setrlimit(RLIMIT_FSIZE, &saved);
    std::signal(SIGXFSZ, savedHandler);
  }

private:
  struct rlimit saved;
  void (*savedHandler)(int);
};

TEST(CSV, AFullDiskNamesTheFileAndKeepsTheOldOne) {
  Set set("s");
  auto x = set.addField<double, 3>("x");
  for (int i = 0; i < 1000; ++i)
    x.set(set.add(), {1.0 / 3, 2, 3});
  TempDir dir;
  dir.write("x.csv", "element,x_0,x_1,x_2\n0,1,2,3\n");
  std::string err;
  {
    FileSizeLimit limit(4096);
    err = errorOf(writeCSV(dir.path("x.csv"), set, {"x"}));
  }
  EXPECT_THAT(err, HasSubstr("x.csv: cannot write: File too large"));
  EXPECT_EQ(readFile(dir.path("x.csv")), "element,x_0,x_1,x_2\n0,1,2,3\n");
}

TEST(SceneOutput, WritesFramesAsTheSceneSays) {
  TempDir dir;
  dir.write("m.node", "4 3 0 0\n0 0 0 0\n1 1 0 0\n2 0 1 0\n3 0 0 1\n");
  dir.write("m.ele", "1 4 0\n0 0 1 2 3\n");
  auto scene = loadScene(dir.write("scene.json", R"({
    "meshes": {"m": "m.node"},
    "sets": {
      "verts": {"mesh": "m", "fields": {"x": {"coordinates": "mesh"},
                                        "c": {"type": "int32", "value": 0}}},
      "tets": {"mesh": "m", "elements": "tets", "endpoints": "verts"}
    },
    "step": "step", "frames": 4,
    "outputs": [
      {"format": "vtk", "path": "vtk/f{frame}.vtu", "set": "verts",
       "cells": "tets", "fields": "c", "every": 2},
      {"format": "csv", "path": "all.csv", "set": "verts", "fields": ["c"]},
      {"format": "csv", "path": "csv/c{frame}.csv", "set": "verts",
       "fields": ["c"], "last": true}
    ]
  })"));
  ASSERT_TRUE(bool(scene)) << llvm::toString(scene.takeError());
  SetRegistry registry;
  ASSERT_FALSE(bool(buildSets(*scene, registry)));
  std::string out = dir.path("out");
  auto writer = SceneOutputWriter::create(*scene, registry, out, 4);
  ASSERT_TRUE(bool(writer)) << llvm::toString(writer.takeError());
  auto c = registry.find("verts")->field<int32_t>("c");
  for (int frame = 0; frame <= 4; ++frame) {
    for (int p = 0; p < 4; ++p)
      c.set(p, frame * 10 + p);
    ASSERT_FALSE(bool((*writer)->writeFrame(frame, frame == 4)));
  }
  // The CSV with every frame appears when the run finishes.
  EXPECT_FALSE(llvm::sys::fs::exists(out + "/all.csv"));
  ASSERT_FALSE(bool((*writer)->finish()));
  // VTK at frames 0, 2, 4; the last-only CSV; the CSV with every frame.
  std::vector<std::string> expected = {
      out + "/vtk/f0.vtu", out + "/vtk/f2.vtu", out + "/vtk/f4.vtu",
      out + "/csv/c4.csv", out + "/all.csv"};
  EXPECT_EQ((*writer)->writtenFiles(), expected);
  EXPECT_EQ(dataArray(readFile(out + "/vtk/f2.vtu"), "Name=\"c\""),
            (std::vector<double>{20, 21, 22, 23}));
  std::string all = readFile(out + "/all.csv");
  EXPECT_THAT(all, HasSubstr("frame,element,c\n0,0,0\n0,1,1\n"));
  EXPECT_THAT(all, HasSubstr("\n3,2,32\n"));
  EXPECT_THAT(all, HasSubstr("\n4,3,43\n"));
  EXPECT_EQ(readFile(out + "/csv/c4.csv"),
            "element,c\n0,40\n1,41\n2,42\n3,43\n");
}

TEST(SceneOutput, FieldsAreCheckedAgainstTheBuiltSets) {
  TempDir dir;
  auto scene = loadScene(dir.write("scene.json", R"({
    "sets": {"p": {"size": 2}},
    "outputs": [{"format": "csv", "path": "p.csv", "set": "p",
                 "fields": ["v"]}]
  })"));
  ASSERT_TRUE(bool(scene)) << llvm::toString(scene.takeError());
  SetRegistry registry;
  ASSERT_FALSE(bool(buildSets(*scene, registry)));
  std::string err =
      errorOf(SceneOutputWriter::create(*scene, registry, dir.path("o"), 0));
  EXPECT_THAT(err, HasSubstr("scene.json: outputs[0]: CSV output of set 'p': "
                             "no field 'v'"));
}

/// The names in `directory`, sorted.
std::vector<std::string> filesIn(const std::string &directory) {
  std::vector<std::string> names;
  std::error_code ec;
  for (llvm::sys::fs::directory_iterator it(directory, ec), end;
       it != end && !ec; it.increment(ec))
    names.push_back(llvm::sys::path::filename(it->path()).str());
  std::sort(names.begin(), names.end());
  return names;
}

TEST(SceneOutput, AFailedRunKeepsTheFilesOfTheLastRun) {
  TempDir dir;
  auto scene = loadScene(dir.write("scene.json", R"({
    "sets": {"p": {"size": 2, "fields": {"c": {"type": "int32",
                                                "value": 7}}}},
    "step": "step", "frames": 2,
    "outputs": [
      {"format": "csv", "path": "all.csv", "set": "p", "fields": ["c"]},
      {"format": "csv", "path": "last.csv", "set": "p", "fields": ["c"],
       "last": true}
    ]
  })"));
  ASSERT_TRUE(bool(scene)) << llvm::toString(scene.takeError());
  SetRegistry registry;
  ASSERT_FALSE(bool(buildSets(*scene, registry)));
  std::string out = dir.path("out");
  llvm::sys::fs::create_directories(out);
  std::string earlier = "element,c\n0,1\n";
  dir.write("out/all.csv", earlier);
  dir.write("out/last.csv", earlier);
  {
    // A run that stops after frame 1: the writer goes without finish().
    auto writer = SceneOutputWriter::create(*scene, registry, out, 2);
    ASSERT_TRUE(bool(writer)) << llvm::toString(writer.takeError());
    ASSERT_FALSE(bool((*writer)->writeFrame(0, false)));
    ASSERT_FALSE(bool((*writer)->writeFrame(1, false)));
    EXPECT_EQ(readFile(out + "/all.csv"), earlier);
  }
  EXPECT_EQ(readFile(out + "/all.csv"), earlier);
  EXPECT_EQ(readFile(out + "/last.csv"), earlier);
  // Nothing else is left behind.
  EXPECT_EQ(filesIn(out), (std::vector<std::string>{"all.csv", "last.csv"}));
}

TEST(SceneOutput, OutputsWritingOneFileAreAnError) {
  TempDir dir;
  auto errorFor = [&](llvm::StringRef outputs, int frames) {
    auto scene = loadScene(dir.write(
        "scene.json", (R"({"sets": {"p": {"size": 1, "fields": {"x":
                           {"shape": [3]}}}}, "step": "s", "frames": 3,
                           "outputs": [)" +
                       outputs + "]}")
                          .str()));
    if (!scene)
      return llvm::toString(scene.takeError());
    SetRegistry registry;
    if (llvm::Error err = buildSets(*scene, registry))
      return llvm::toString(std::move(err));
    auto writer =
        SceneOutputWriter::create(*scene, registry, dir.path("o"), frames);
    return writer ? std::string() : llvm::toString(writer.takeError());
  };
  std::string csv = R"("format": "csv", "set": "p", "fields": ["x"])";
  std::string err = errorFor("{" + csv + R"(, "path": "a.csv"}, {)" + csv +
                                 R"(, "path": "./sub/../a.csv"})",
                             3);
  EXPECT_THAT(err, HasSubstr("scene.json: outputs[1].path: writes "));
  EXPECT_THAT(err, HasSubstr("/o/a.csv, which outputs[0] writes too"));
  // "x{frame}.csv" at frame 10 is "x1{frame}.csv" at frame 0.
  std::string frames = "{" + csv + R"(, "path": "x{frame}.csv"}, {)" + csv +
                       R"(, "path": "x1{frame}.csv"})";
  EXPECT_THAT(errorFor(frames, 12), HasSubstr("/o/x10.csv, which outputs[0] "
                                              "writes too"));
  EXPECT_EQ(errorFor(frames, 9), "");
  // A file of its own name meets a frame's file; "every" decides which.
  std::string fixed = "{" + csv + R"(, "path": "x{frame}.csv", "every": 2},
                       {)" + csv + R"(, "path": "x8.csv"})";
  EXPECT_THAT(errorFor(fixed, 9), HasSubstr("outputs[1].path: writes "));
  EXPECT_THAT(errorFor(fixed, 9), HasSubstr("/o/x8.csv, which outputs[0] "
                                            "writes too"));
  EXPECT_EQ(errorFor(fixed, 7), "");
  // Paths that cannot meet are not walked frame by frame: two billion
  // frames take no time.
  EXPECT_EQ(errorFor("{" + csv + R"(, "path": "a{frame}.csv"}, {)" + csv +
                         R"(, "path": "b{frame}.csv"})",
                     2000000000),
            "");
  // Standard output may be shared.
  EXPECT_EQ(errorFor("{" + csv + R"(, "path": "-"}, {)" + csv +
                         R"(, "path": "-"})",
                     3),
            "");
}

} // namespace
