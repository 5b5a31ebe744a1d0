//===--- SceneTest.cpp - Scene parsing, checking and set building ---------===//

#include "simit/Runtime/Scene.h"

#include "TestFiles.h"

#include "gmock/gmock.h"

#include "llvm/Support/MemoryBuffer.h"

#include <cmath>
#include <sys/resource.h>

using namespace simit;
using namespace simit::test;
using ::testing::HasSubstr;

namespace {

/// Two tets sharing the face (1, 2, 3); z ranges over [0, 2].
const char *kPyramidNode = "5 3 0 0\n"
                           "0 0 0 0\n"
                           "1 1 0 0\n"
                           "2 0 1 0\n"
                           "3 0 0 1\n"
                           "4 1 1 2\n";
const char *kPyramidEle = "2 4 0\n0 0 1 2 3\n1 1 2 3 4\n";

class SceneTest : public ::testing::Test {
protected:
  void SetUp() override {
    dir.write("pyramid.node", kPyramidNode);
    dir.write("pyramid.ele", kPyramidEle);
  }

  llvm::Expected<SceneDescription> parse(llvm::StringRef json) {
    return loadScene(dir.write("scene.json", json));
  }

  /// The error of parsing `json`, with the temporary directory removed.
  std::string parseError(llvm::StringRef json) {
    std::string message = errorOf(parse(json));
    size_t at = message.find(dir.path("scene.json"));
    if (at != std::string::npos)
      message.replace(at, dir.path("scene.json").size(), "scene.json");
    return message;
  }

  /// Parses and builds; the error of either step.
  std::string buildError(llvm::StringRef json) {
    auto scene = parse(json);
    if (!scene)
      return "parse: " + llvm::toString(scene.takeError());
    SetRegistry registry;
    std::string message = errorOf(buildSets(*scene, registry));
    size_t at = message.find(dir.path("scene.json"));
    if (at != std::string::npos)
      message.replace(at, dir.path("scene.json").size(), "scene.json");
    return message;
  }

  TempDir dir;
};

const char *kFullScene = R"({
  "program": "fem.sim",
  "meshes": { "pyramid": "pyramid.node" },
  "sets": {
    "verts": {
      "mesh": "pyramid",
      "fields": {
        "x":     { "coordinates": "mesh" },
        "xn":    { "coordinates": "normalized", "type": "float32" },
        "v":     [0.5, 0, -1],
        "m":     2.5,
        "c":     { "type": "int32", "expr": "z < 0.1 * max_z" },
        "fixed": { "type": "bool", "expr": "z < 0.1", "space": "normalized" },
        "vel":   { "if": "x > 0.5", "then": [0.1, 0, 0.1], "else": [0, 0, 0] },
        "w":     { "file": "weights.txt" },
        "depth": { "expr": "max_z - z" },
        "zero":  { "shape": [2, 2] }
      }
    },
    "tets": {
      "mesh": "pyramid", "elements": "tets", "endpoints": "verts",
      "fields": {
        "B": { "value": [[1, 0, 0], [0, 1, 0], [0, 0, 1]] },
        "top": { "type": "bool", "expr": "z > 0.5" },
        "id": { "type": "int32", "file": "ids.txt" }
      }
    }
  },
  "externs": {
    "h": 0.01,
    "grav": [0, -9.81, 0],
    "cgMaxIters": { "type": "int32", "value": 50 },
    "verbose": false
  },
  "init": "init",
  "step": ["step", "post"],
  "frames": 3,
  "outputs": [
    { "format": "vtk", "path": "out/pyramid_{frame}.vtu", "set": "verts",
      "cells": "tets", "fields": ["v", "c"], "cell_fields": ["top"] },
    { "format": "csv", "path": "out/x.csv", "set": "verts", "fields": ["x"],
      "every": 2 },
    { "format": "csv", "path": "final.csv", "set": "tets", "fields": ["B"],
      "last": true }
  ]
})";

TEST_F(SceneTest, ParsesEverySection) {
  auto scene = parse(kFullScene);
  ASSERT_TRUE(bool(scene)) << llvm::toString(scene.takeError());
  EXPECT_EQ(scene->program, dir.path("fem.sim"));
  ASSERT_EQ(scene->meshes.size(), 1u);
  EXPECT_EQ(scene->meshes[0].path, dir.path("pyramid.node"));
  ASSERT_EQ(scene->sets.size(), 2u);
  EXPECT_EQ(scene->sets[0].kind, SetSpec::Points);
  EXPECT_EQ(scene->sets[1].kind, SetSpec::Elements);
  EXPECT_EQ(scene->sets[1].endpoints, std::vector<std::string>{"verts"});
  EXPECT_EQ(scene->sets[0].fields.size(), 10u);
  EXPECT_EQ(scene->init, std::vector<std::string>{"init"});
  EXPECT_EQ(scene->step, (std::vector<std::string>{"step", "post"}));
  EXPECT_EQ(scene->frames, 3);
  ASSERT_EQ(scene->outputs.size(), 3u);
  EXPECT_EQ(scene->outputs[0].kind, OutputSpec::VTK);
  EXPECT_EQ(scene->outputs[0].cells, std::vector<std::string>{"tets"});
  EXPECT_EQ(scene->outputs[1].every, 2);
  EXPECT_TRUE(scene->outputs[2].lastOnly);
  const FieldSpec &v = scene->sets[0].fields[2];
  EXPECT_EQ(v.shape, std::vector<int>{3});
  EXPECT_EQ(v.init.kind, FieldInit::Constant);
  const FieldSpec &b = scene->sets[1].fields[0];
  EXPECT_EQ(b.shape, (std::vector<int>{3, 3}));
}

TEST_F(SceneTest, BuildsSetsFieldsAndExterns) {
  dir.write("weights.txt", "# one weight per vertex\n1 2\n3\n4 5\n");
  dir.write("ids.txt", "7 8\n");
  auto scene = parse(kFullScene);
  ASSERT_TRUE(bool(scene)) << llvm::toString(scene.takeError());
  SetRegistry registry;
  ASSERT_FALSE(bool(buildSets(*scene, registry)));

  Set *verts = registry.find("verts");
  Set *tets = registry.find("tets");
  ASSERT_TRUE(verts && tets);
  ASSERT_EQ(verts->size(), 5);
  ASSERT_EQ(tets->size(), 2);
  EXPECT_EQ(&tets->endpointSet(3), verts);
  EXPECT_EQ(tets->endpoint(1, 3), 4);
  ASSERT_NE(registry.meshOf("tets"), nullptr);
  EXPECT_EQ(registry.meshOf("tets")->tets.size(), 2u);

  auto x = verts->field<double, 3>("x");
  using Vec3 = std::array<double, 3>;
  using Vec3f = std::array<float, 3>;
  EXPECT_EQ(x.get(4), (Vec3{1, 1, 2}));
  // Normalised per axis: z in [0, 2] becomes [0, 1].
  auto xn = verts->field<float, 3>("xn");
  EXPECT_EQ(xn.get(4), (Vec3f{1, 1, 1}));
  EXPECT_EQ(xn.get(3), (Vec3f{0, 0, 0.5f}));
  EXPECT_EQ((verts->field<double, 3>("v").get(2)), (Vec3{0.5, 0, -1}));
  EXPECT_EQ(verts->field<double>("m").get(0), 2.5);
  auto c = verts->field<int32_t>("c");
  auto fixed = verts->field<bool>("fixed");
  auto vel = verts->field<double, 3>("vel");
  auto depth = verts->field<double>("depth");
  auto w = verts->field<double>("w");
  for (int p = 0; p < 5; ++p) {
    std::array<double, 3> position = x.get(p);
    EXPECT_EQ(c.get(p), position[2] < 0.2 ? 1 : 0) << p;
    EXPECT_EQ(fixed.get(p), position[2] / 2 < 0.1) << p;
    EXPECT_EQ(vel.get(p), position[0] > 0.5 ? (Vec3{0.1, 0, 0.1}) : Vec3{})
        << p;
    EXPECT_EQ(depth.get(p), 2 - position[2]) << p;
    EXPECT_EQ(w.get(p), p + 1.0) << p;
  }
  EXPECT_EQ(verts->fieldDescriptor("zero")->blockSize(), 4u);

  // Tet fields: centroid z of tet 0 is 0.25, of tet 1 is 0.75.
  auto top = tets->field<bool>("top");
  EXPECT_FALSE(top.get(0));
  EXPECT_TRUE(top.get(1));
  EXPECT_EQ(tets->field<int32_t>("id").get(1), 8);
  EXPECT_EQ((tets->field<double, 3, 3>("B").get(1)[4]), 1.0);

  ExternTensor *h = registry.findExtern("h");
  ASSERT_NE(h, nullptr);
  EXPECT_TRUE(h->shape.empty());
  EXPECT_EQ(*static_cast<const double *>(h->data()), 0.01);
  ExternTensor *grav = registry.findExtern("grav");
  ASSERT_NE(grav, nullptr);
  EXPECT_EQ(grav->shape, std::vector<int>{3});
  EXPECT_EQ(static_cast<const double *>(grav->data())[1], -9.81);
  ExternTensor *iters = registry.findExtern("cgMaxIters");
  ASSERT_NE(iters, nullptr);
  EXPECT_EQ(iters->type, ComponentType::Int32);
  EXPECT_EQ(*static_cast<const int32_t *>(iters->data()), 50);
  EXPECT_EQ(registry.findExtern("verbose")->type, ComponentType::Bool);
}

TEST_F(SceneTest, ExternConversion) {
  ExternTensor tensor;
  tensor.shape = {2};
  tensor.values = {50, 1};
  tensor.store();
  ASSERT_FALSE(bool(tensor.convertTo(ComponentType::Int32)));
  EXPECT_EQ(static_cast<const int32_t *>(tensor.data())[0], 50);
  EXPECT_THAT(errorOf(tensor.convertTo(ComponentType::Bool)),
              HasSubstr("component 0: expected a bool value (0 or 1), found "
                        "50"));
  tensor.values = {0.5, 1};
  EXPECT_THAT(errorOf(tensor.convertTo(ComponentType::Int32)),
              HasSubstr("component 0: expected an int32 value, found 0.5"));
  ASSERT_FALSE(bool(tensor.convertTo(ComponentType::Float32)));
  EXPECT_EQ(static_cast<const float *>(tensor.data())[0], 0.5f);
}

TEST_F(SceneTest, RefinedMeshAndSizedAndGridSets) {
  auto scene = parse(R"({
    "meshes": { "p": { "file": "pyramid.ele", "refine": 1 } },
    "sets": {
      "verts": { "mesh": "p" },
      "tets": { "mesh": "p", "elements": "tets", "endpoints": "verts" },
      "cells": { "size": 6, "fields": { "k": 3 } },
      "links": { "grid": [2, 3], "endpoints": "cells" }
    }
  })");
  ASSERT_TRUE(bool(scene)) << llvm::toString(scene.takeError());
  SetRegistry registry;
  ASSERT_FALSE(bool(buildSets(*scene, registry)));
  // 5 points and 9 distinct edges; 2 tets become 16.
  EXPECT_EQ(registry.find("verts")->size(), 14);
  EXPECT_EQ(registry.find("tets")->size(), 16);
  EXPECT_EQ(registry.find("cells")->field<double>("k").get(5), 3.0);
  Set *links = registry.find("links");
  EXPECT_TRUE(links->isGrid());
  EXPECT_EQ(links->size(), 12);
}

TEST_F(SceneTest, ListedEdgeSetsAndPerElementValues) {
  // Heterogeneous links (particles, nodes) and faces over the edges of a
  // triangle: endpoint sets may be edge sets, listed in any order.
  auto scene = parse(R"({
    "sets": {
      "faces": { "elements": [[0, 1, 2]], "endpoints": "edges" },
      "edges": { "elements": [[0, 1], [1, 2], [2, 0]], "endpoints": "nodes",
                 "fields": { "k": { "values": [1.5, 2, 3] } } },
      "links": { "elements": [[1, 0], [0, 2]],
                 "endpoints": ["particles", "nodes"] },
      "particles": { "size": 2, "fields": {
        "x": { "values": [[1, 2, 3], [4, 5, 6]] },
        "c": { "type": "int32", "values": [7, -1] } } },
      "nodes": { "size": 3 }
    }
  })");
  ASSERT_TRUE(bool(scene)) << llvm::toString(scene.takeError());
  SetRegistry registry;
  ASSERT_FALSE(bool(buildSets(*scene, registry)));
  Set *links = registry.find("links");
  ASSERT_EQ(links->cardinality(), 2);
  EXPECT_EQ(&links->endpointSet(0), registry.find("particles"));
  EXPECT_EQ(&links->endpointSet(1), registry.find("nodes"));
  EXPECT_EQ(std::vector<int32_t>(links->endpointData(),
                                 links->endpointData() + 4),
            (std::vector<int32_t>{1, 0, 0, 2}));
  Set *faces = registry.find("faces");
  EXPECT_EQ(&faces->endpointSet(2), registry.find("edges"));
  EXPECT_EQ(registry.find("edges")->field<double>("k").get(0), 1.5);
  EXPECT_EQ(registry.find("edges")->field<double>("k").get(2), 3.0);
  auto x = registry.find("particles")->field<double, 3>("x");
  EXPECT_EQ(x.get(1)[2], 6.0);
  EXPECT_EQ(registry.find("particles")->field<int32_t>("c").get(1), -1);
}

TEST_F(SceneTest, ListedEdgeSetErrors) {
  auto withSets = [&](llvm::StringRef sets) {
    return buildError(("{\"sets\": {\"p\": {\"size\": 2}, " + sets + "}}")
                          .str());
  };
  EXPECT_THAT(withSets(R"("e": {"elements": [[0, 1], [1]], "endpoints": "p"})"),
              HasSubstr("sets.e.elements[1]: expected 2 endpoints, as in "
                        "element 0, found 1"));
  EXPECT_THAT(withSets(R"("e": {"elements": [[0, -1]], "endpoints": "p"})"),
              HasSubstr("sets.e.elements[0][1]: expected an integer of at "
                        "least 0"));
  EXPECT_THAT(withSets(R"("e": {"elements": [[0, 1]], "endpoints": ["p"]})"),
              HasSubstr("sets.e.endpoints: expected 2 set names, one per "
                        "endpoint of an element, found 1"));
  EXPECT_THAT(withSets(R"("e": {"elements": [], "endpoints": "p"})"),
              HasSubstr("sets.e.endpoints: expected an array naming the set "
                        "of each endpoint"));
  EXPECT_THAT(withSets(R"("e": {"elements": [[0, 1]], "endpoints": ["p", "f"]},
                          "f": {"elements": [[0, 0]], "endpoints": ["e", "p"]})"),
              HasSubstr("expected endpoint sets that do not lead back to"));
  EXPECT_THAT(withSets(R"("e": {"elements": [[0, 2]], "endpoints": "p"})"),
              HasSubstr("sets.e.elements[0]:"));
  EXPECT_THAT(withSets(R"("e": {"elements": [[0, 1]], "endpoints": "p",
                                "fields": {"k": {"values": [1, 2]}}})"),
              HasSubstr("sets.e.fields.k.values: expected 1 values, one per "
                        "element of the set, found 2"));
  EXPECT_THAT(withSets(R"("q": {"size": 2, "fields": {"k": {"values": [1, [2, 3]]}}})"),
              HasSubstr("sets.q.fields.k.values[1]: expected a single number"));
}

TEST_F(SceneTest, SpringsBunnyFixedPoints) {
  // The springs-bunny rule of scenes.md: normalised z < 0.1.
  std::string json = R"({
    "meshes": { "bunny": ")" +
                     sharedPath("data/meshes/bunny.1.node") + R"(" },
    "sets": {
      "points": { "mesh": "bunny", "fields": {
        "x": { "coordinates": "normalized" },
        "c": { "type": "int32", "expr": "z < 0.1", "space": "normalized" } } },
      "springs": { "mesh": "bunny", "elements": "edges", "endpoints": "points" }
    }
  })";
  auto scene = parse(json);
  ASSERT_TRUE(bool(scene)) << llvm::toString(scene.takeError());
  SetRegistry registry;
  ASSERT_FALSE(bool(buildSets(*scene, registry)));
  Set *points = registry.find("points");
  ASSERT_EQ(points->size(), 3607);
  EXPECT_EQ(registry.find("springs")->size(), 19233);
  // Independently: the z range from the raw mesh.
  auto mesh = loadTetGen(sharedPath("data/meshes/bunny.1"));
  ASSERT_TRUE(bool(mesh));
  double lo = INFINITY, hi = -INFINITY;
  for (const auto &p : mesh->points) {
    lo = std::min(lo, p[2]);
    hi = std::max(hi, p[2]);
  }
  auto c = points->field<int32_t>("c");
  auto x = points->field<double, 3>("x");
  int count = 0;
  for (int p = 0; p < points->size(); ++p) {
    double z = (mesh->points[p][2] - lo) / (hi - lo);
    EXPECT_DOUBLE_EQ(x.get(p)[2], z);
    EXPECT_EQ(c.get(p), z < 0.1 ? 1 : 0);
    count += c.get(p);
  }
  EXPECT_GT(count, 0);
  EXPECT_LT(count, 3607);
}

TEST_F(SceneTest, TheDocumentedExampleParses) {
  // The first JSON block of docs/scene-format.md, resolved from docs/.
  std::string docs = SIMIT_SOURCE_DIR "/docs";
  auto buffer = llvm::MemoryBuffer::getFile(docs + "/scene-format.md");
  ASSERT_TRUE(bool(buffer));
  llvm::StringRef text = (*buffer)->getBuffer();
  size_t begin = text.find("```json\n");
  ASSERT_NE(begin, llvm::StringRef::npos);
  begin += 8;
  llvm::StringRef json = text.slice(begin, text.find("```", begin));
  auto scene = parseScene(json, "scene-format.md", docs);
  ASSERT_TRUE(bool(scene)) << llvm::toString(scene.takeError());
  EXPECT_EQ(scene->sets.size(), 2u);
  EXPECT_EQ(scene->externs.size(), 8u);
  EXPECT_EQ(scene->outputs.size(), 2u);
}

//===--- Parse errors -----------------------------------------------------===//

TEST_F(SceneTest, InvalidJsonNamesLineAndColumn) {
  EXPECT_THAT(parseError("{\n  \"sets\": {,\n}"),
              HasSubstr("scene.json:2:12: invalid JSON:"));
}

TEST_F(SceneTest, MissingFileIsAnError) {
  EXPECT_THAT(errorOf(loadScene(dir.path("absent.json"))),
              HasSubstr("absent.json: cannot open"));
}

TEST_F(SceneTest, TopLevelErrors) {
  EXPECT_THAT(parseError("[1]"),
              HasSubstr("scene.json: expected a JSON object, found an array"));
  EXPECT_THAT(parseError("{}"),
              HasSubstr("scene.json: expected a \"sets\" object"));
  EXPECT_THAT(parseError(R"({"sets": {}, "frame": 3})"),
              HasSubstr("scene.json: frame: unknown key (expected one of "
                        "program, libraries, meshes, sets"));
  EXPECT_THAT(parseError(R"({"sets": {}, "frames": -1, "step": "s"})"),
              HasSubstr("scene.json: frames: expected an integer of at least "
                        "0"));
  EXPECT_THAT(parseError(R"({"sets": {}, "frames": 2})"),
              HasSubstr("scene.json: frames: expected a \"step\" function"));
  EXPECT_THAT(parseError(R"({"sets": {}, "init": 3})"),
              HasSubstr("scene.json: init: expected a name or an array of "
                        "names, found a number"));
  EXPECT_THAT(parseError(R"({"sets": {}, "step": ["a", ""]})"),
              HasSubstr("scene.json: step[1]: expected a non-empty string"));
}

TEST_F(SceneTest, MeshAndSetErrors) {
  EXPECT_THAT(parseError(R"({"meshes": {"m": 3}, "sets": {}})"),
              HasSubstr("scene.json: meshes.m: expected a file name or an "
                        "object, found a number"));
  EXPECT_THAT(parseError(R"({"meshes": {"m": {"file": "a", "refine": -1}},
                             "sets": {}})"),
              HasSubstr("scene.json: meshes.m.refine: expected an integer "
                        "from 0 to 10"));
  EXPECT_THAT(parseError(R"({"sets": {"p": {"mesh": "nope"}}})"),
              HasSubstr("scene.json: sets.p.mesh: expected the name of a mesh "
                        "in \"meshes\", found \"nope\""));
  EXPECT_THAT(parseError(R"({"sets": {"p": {}}})"),
              HasSubstr("scene.json: sets.p: expected exactly one of \"mesh\", "
                        "\"size\", \"grid\" or an \"elements\" array"));
  EXPECT_THAT(parseError(R"({"sets": {"p": {"size": 2, "elements": "tets"}}})"),
              HasSubstr("scene.json: sets.p.elements: expected \"elements\" "
                        "only with \"mesh\", or as an array of endpoint index "
                        "lists"));
  EXPECT_THAT(parseError(R"({"sets": {"p": {"size": 2, "feilds": {}}}})"),
              HasSubstr("scene.json: sets.p.feilds: unknown key"));
}

const char *kMeshPrefix = R"({"meshes": {"m": "pyramid.node", "n": "pyramid.node"},
  "sets": {"p": {"mesh": "m"}, "q": {"mesh": "n"}, )";

TEST_F(SceneTest, EndpointErrors) {
  auto withSet = [&](llvm::StringRef set) {
    return parseError((kMeshPrefix + set + "}}}").str());
  };
  EXPECT_THAT(withSet(R"("t": {"mesh": "m", "elements": "tets")"),
              HasSubstr("scene.json: sets.t: expected \"endpoints\": the name "
                        "of the point set"));
  EXPECT_THAT(withSet(R"("t": {"mesh": "m", "elements": "cubes", "endpoints": "p")"),
              HasSubstr("scene.json: sets.t.elements: expected \"edges\", "
                        "\"triangles\" or \"tets\", found \"cubes\""));
  EXPECT_THAT(withSet(R"("t": {"mesh": "m", "elements": "tets", "endpoints": "r")"),
              HasSubstr("scene.json: sets.t.endpoints: expected the name of a "
                        "set in \"sets\", found \"r\""));
  EXPECT_THAT(withSet(R"("t": {"mesh": "m", "elements": "tets", "endpoints": "q")"),
              HasSubstr("scene.json: sets.t.endpoints: expected a set of the "
                        "points of mesh \"m\""));
  EXPECT_THAT(withSet(R"("t": {"mesh": "m", "elements": "tets", "endpoints": "p"},
                         "u": {"mesh": "m", "elements": "tets", "endpoints": "t")"),
              HasSubstr("scene.json: sets.u.endpoints: expected a vertex set, "
                        "found the edge set \"t\""));
  EXPECT_THAT(withSet(R"("t": {"mesh": "m", "endpoints": "p")"),
              HasSubstr("scene.json: sets.t: expected \"endpoints\" only with "
                        "\"elements\" or \"grid\""));
}

/// The error of a scene whose set "p" (points of the pyramid) has `fields`.
std::string fieldScene(llvm::StringRef fields) {
  return (R"({"meshes": {"m": "pyramid.node"}, "sets": {"p": {"mesh": "m", )"
          R"("fields": {)" +
          fields + "}}, \"cells\": {\"size\": 2}}}")
      .str();
}

TEST_F(SceneTest, ConstantFieldErrors) {
  EXPECT_THAT(parseError(fieldScene(R"("x": {"shape": [3], "value": [1, 2]})")),
              HasSubstr("scene.json: sets.p.fields.x.value: expected an array "
                        "of 3 numbers, found an array of shape [2]"));
  EXPECT_THAT(parseError(fieldScene(R"("x": {"shape": [3], "value": 1})")),
              HasSubstr("expected an array of 3 numbers, found a single "
                        "value"));
  EXPECT_THAT(parseError(fieldScene(R"("B": {"shape": [2, 2], "value": [1, 2, 3]})")),
              HasSubstr("scene.json: sets.p.fields.B.value: expected an array "
                        "of shape [2, 2] (or a flat array of 4) of numbers"));
  EXPECT_THAT(parseError(fieldScene(R"("x": [[1, 2], [3]])")),
              HasSubstr("scene.json: sets.p.fields.x[1]: expected shape [2] "
                        "like the first entry, found [1]"));
  EXPECT_THAT(parseError(fieldScene(R"("x": [])")),
              HasSubstr("scene.json: sets.p.fields.x: expected a number, a "
                        "boolean or a non-empty array of them, found an "
                        "empty array"));
  EXPECT_THAT(parseError(fieldScene(R"("x": "fast")")),
              HasSubstr("found a string"));
  EXPECT_THAT(parseError(fieldScene(R"("c": {"type": "int32", "value": 1.5})")),
              HasSubstr("scene.json: sets.p.fields.c.value: expected integers "
                        "for an int32 value"));
  EXPECT_THAT(parseError(fieldScene(R"("c": {"type": "bool", "value": 1})")),
              HasSubstr("expected true or false for a bool value"));
  EXPECT_THAT(parseError(fieldScene(R"("c": {"value": true})")),
              HasSubstr("expected numbers for a float64 value, found a "
                        "boolean"));
  EXPECT_THAT(parseError(fieldScene(R"("c": {"type": "double3"})")),
              HasSubstr("scene.json: sets.p.fields.c.type: expected float64, "
                        "float32, int32 or bool, found \"double3\""));
  EXPECT_THAT(parseError(fieldScene(R"("c": {"shape": [3, 0]})")),
              HasSubstr("scene.json: sets.p.fields.c.shape[1]: expected an "
                        "integer of at least 1"));
}

TEST_F(SceneTest, InitialiserErrors) {
  EXPECT_THAT(parseError(fieldScene(R"("x": {"value": 1, "file": "f"})")),
              HasSubstr("scene.json: sets.p.fields.x: expected one of value, "
                        "values, coordinates, file, expr or if, found both \"value\" "
                        "and \"file\""));
  EXPECT_THAT(parseError(fieldScene(R"("x": {"coordinates": "raw"})")),
              HasSubstr("scene.json: sets.p.fields.x.coordinates: expected "
                        "\"mesh\" or \"normalized\", found \"raw\""));
  EXPECT_THAT(parseError(fieldScene(R"("x": {"coordinates": "mesh", "shape": [2]})")),
              HasSubstr("scene.json: sets.p.fields.x: expected a float64 or "
                        "float32 field of shape [3] for coordinates"));
  EXPECT_THAT(parseError(fieldScene(R"("f": {"expr": "z <"})")),
              HasSubstr("scene.json: sets.p.fields.f.expr: column 4: expected "
                        "a number, a name or '('"));
  EXPECT_THAT(parseError(fieldScene(R"("f": {"type": "bool", "expr": "z + 1"})")),
              HasSubstr("scene.json: sets.p.fields.f.expr: expected a boolean "
                        "expression for a bool field"));
  EXPECT_THAT(parseError(fieldScene(R"("f": {"shape": [3], "expr": "z"})")),
              HasSubstr("expected a scalar field (shape []) for \"expr\""));
  EXPECT_THAT(parseError(fieldScene(R"("f": {"if": "z", "then": 1, "else": 0})")),
              HasSubstr("scene.json: sets.p.fields.f.if: expected a boolean "
                        "condition"));
  EXPECT_THAT(parseError(fieldScene(R"("f": {"if": "z < 1", "then": 1})")),
              HasSubstr("expected both \"then\" and \"else\" with \"if\""));
  EXPECT_THAT(parseError(fieldScene(R"("f": {"if": "z < 1", "then": [1, 2], "else": 0})")),
              HasSubstr("scene.json: sets.p.fields.f.else: expected an array "
                        "of 2 numbers"));
  EXPECT_THAT(parseError(fieldScene(R"("f": {"value": 1, "then": 1})")),
              HasSubstr("expected \"then\" and \"else\" only with \"if\""));
  EXPECT_THAT(parseError(fieldScene(R"("f": {"value": 1, "space": "normalized"})")),
              HasSubstr("expected \"space\" only with \"expr\" or \"if\""));
  EXPECT_THAT(parseError(fieldScene(R"("f": {"expr": "1", "space": "unit"})")),
              HasSubstr("scene.json: sets.p.fields.f.space: expected \"mesh\" "
                        "or \"normalized\", found \"unit\""));
  // Sets without a mesh have no coordinates.
  EXPECT_THAT(parseError(R"({"sets": {"c": {"size": 2, "fields":
                             {"f": {"expr": "x"}}}}})"),
              HasSubstr("scene.json: sets.c.fields.f.expr: expected a set "
                        "built from a mesh, which has coordinates"));
}

TEST_F(SceneTest, ExternErrors) {
  EXPECT_THAT(parseError(R"({"sets": {}, "externs": {"g": [0, "x", 0]}})"),
              HasSubstr("scene.json: externs.g[1]: expected a number, a "
                        "boolean or a non-empty array of them, found a "
                        "string"));
  EXPECT_THAT(parseError(R"({"sets": {}, "externs": {"n": {"type": "int32",
                             "value": 2.5}}})"),
              HasSubstr("scene.json: externs.n.value: expected integers for "
                        "an int32 value"));
  EXPECT_THAT(parseError(R"({"sets": {}, "externs": {"n": {"type": "int32"}}})"),
              HasSubstr("scene.json: externs.n: expected a \"value\""));
  EXPECT_THAT(parseError(R"({"sets": {}, "externs": {"n": {"value": 1, "unit": "m"}}})"),
              HasSubstr("scene.json: externs.n.unit: unknown key"));
}

TEST_F(SceneTest, OutputErrors) {
  auto withOutput = [&](llvm::StringRef output) {
    return parseError(
        (R"({"meshes": {"m": "pyramid.node"}, "sets": {"p": {"mesh": "m"},
            "t": {"mesh": "m", "elements": "tets", "endpoints": "p"},
            "c": {"size": 1}},
            "outputs": [)" +
         output + "]}")
            .str());
  };
  EXPECT_THAT(withOutput(R"({"format": "png", "path": "a", "set": "p"})"),
              HasSubstr("scene.json: outputs[0].format: expected \"vtk\" or "
                        "\"csv\", found \"png\""));
  EXPECT_THAT(withOutput(R"({"format": "csv", "set": "p"})"),
              HasSubstr("scene.json: outputs[0]: expected a \"path\""));
  EXPECT_THAT(withOutput(R"({"format": "csv", "path": "a", "set": "q"})"),
              HasSubstr("scene.json: outputs[0].set: expected the name of a "
                        "set in \"sets\", found \"q\""));
  EXPECT_THAT(withOutput(R"({"format": "vtk", "path": "a.vtu", "set": "p"})"),
              HasSubstr("scene.json: outputs[0].path: expected \"{frame}\" in "
                        "the path"));
  EXPECT_THAT(withOutput(R"({"format": "vtk", "path": "a{frame}.vtu", "set": "t"})"),
              HasSubstr("scene.json: outputs[0].set: expected a vertex set "
                        "for VTK output"));
  EXPECT_THAT(withOutput(R"({"format": "vtk", "path": "a{frame}", "set": "p",
                             "cells": ["t", "c"]})"),
              HasSubstr("scene.json: outputs[0].cells[1]: expected an edge "
                        "set over \"p\", found \"c\""));
  EXPECT_THAT(withOutput(R"({"format": "csv", "path": "a", "set": "p",
                             "cells": ["t"]})"),
              HasSubstr("scene.json: outputs[0].cells: expected only with "
                        "\"format\": \"vtk\""));
  EXPECT_THAT(withOutput(R"({"format": "vtk", "path": "a{frame}", "set": "p",
                             "cell_fields": ["w"]})"),
              HasSubstr("scene.json: outputs[0].cell_fields: expected exactly "
                        "one set in \"cells\""));
  EXPECT_THAT(withOutput(R"({"format": "csv", "path": "a", "set": "p",
                             "every": 0})"),
              HasSubstr("scene.json: outputs[0].every: expected an integer of "
                        "at least 1"));
  EXPECT_THAT(withOutput(R"({"format": "csv", "path": "a", "set": "p",
                             "last": 1})"),
              HasSubstr("scene.json: outputs[0].last: expected true or false"));
  EXPECT_THAT(withOutput(R"(3)"),
              HasSubstr("scene.json: outputs[0]: expected an object, found a "
                        "number"));
}

//===--- Build errors -----------------------------------------------------===//

TEST_F(SceneTest, MeshLoadErrorsNameTheMeshAndFile) {
  dir.write("bad.node", "2 3 0 0\n0 0 0 0\n");
  std::string err = buildError(R"({"meshes": {"b": "bad.node"},
                                   "sets": {"p": {"mesh": "b"}}})");
  EXPECT_THAT(err, HasSubstr("scene.json: meshes.b: "));
  EXPECT_THAT(err, HasSubstr("bad.node:3: expected point 2 of 2"));
}

TEST_F(SceneTest, MeshWithoutTheElementsIsAnError) {
  dir.write("points.node", "1 3 0 0\n0 0 0 0\n");
  EXPECT_THAT(buildError(R"({"meshes": {"m": "points.node"}, "sets": {
                  "p": {"mesh": "m"},
                  "t": {"mesh": "m", "elements": "tets", "endpoints": "p"}}})"),
              HasSubstr("scene.json: sets.t.elements: mesh \"m\" has no "
                        "tets"));
}

TEST_F(SceneTest, FieldFileErrors) {
  dir.write("short.txt", "1 2 3\n");
  EXPECT_THAT(buildError(fieldScene(R"("w": {"file": "short.txt"})")),
              HasSubstr("scene.json: sets.p.fields.w.file: "));
  EXPECT_THAT(buildError(fieldScene(R"("w": {"file": "short.txt"})")),
              HasSubstr("short.txt: expected 5 values (5 elements of 1), found "
                        "3"));
  dir.write("long.txt", "1 2 3\n4 5 6\n");
  EXPECT_THAT(buildError(fieldScene(R"("w": {"file": "long.txt"})")),
              HasSubstr("long.txt:2: expected 5 values, found more"));
  dir.write("text.txt", "1 2\nthree 4 5\n");
  EXPECT_THAT(buildError(fieldScene(R"("w": {"file": "text.txt"})")),
              HasSubstr("text.txt:2: expected a number for a field value, "
                        "found 'three'"));
  // Values are finite decimal numbers.
  for (const char *bad : {"nan", "inf", "1e999", "0x10"}) {
    dir.write("bad.txt", std::string("1 2\n3 ") + bad + " 5\n");
    EXPECT_THAT(buildError(fieldScene(R"("w": {"file": "bad.txt"})")),
                HasSubstr(std::string("bad.txt:2: expected a ") +
                          (bad[1] == 'x' ? "number" : "finite number") +
                          " for a field value, found '" + bad + "'"));
  }
  dir.write("ints.txt", "1 2 3 4.5 5\n");
  EXPECT_THAT(buildError(fieldScene(R"("w": {"type": "int32", "file": "ints.txt"})")),
              HasSubstr("ints.txt:1: expected an int32 value, found 4.5"));
  EXPECT_THAT(buildError(fieldScene(R"("w": {"file": "none.txt"})")),
              HasSubstr("none.txt: cannot open"));
}

TEST_F(SceneTest, NonIntegerExpressionForIntFieldIsAnError) {
  EXPECT_THAT(buildError(fieldScene(R"("c": {"type": "int32", "expr": "z / 2"})")),
              HasSubstr("scene.json: sets.p.fields.c.expr: element 3: expected "
                        "an int32 value, found 0.5"));
}

TEST_F(SceneTest, GridOfTheWrongSizeIsAnError) {
  EXPECT_THAT(buildError(R"({"sets": {"c": {"size": 5},
                             "g": {"grid": [2, 2], "endpoints": "c"}}})"),
              HasSubstr("scene.json: sets.g: grid 'g': the point set 'c' has "
                        "5 points, expected 4"));
}

TEST_F(SceneTest, NumbersBeyondDoublesNameTheirPath) {
  EXPECT_THAT(parseError(R"({"sets": {}, "externs": {"h": 1e999}})"),
              HasSubstr("scene.json: externs.h: invalid JSON: number "
                        "overflow parsing '1e999'"));
  EXPECT_THAT(parseError(R"({"sets": {}, "externs": {"g": [0, -1e999]}})"),
              HasSubstr("scene.json: externs.g[1]: invalid JSON: number "
                        "overflow parsing '-1e999'"));
  EXPECT_THAT(parseError(R"({"sets": {"p": {"size": 1, "fields": {"v":
                             {"value": [[1, 2], [3, 1e400]]}}}}})"),
              HasSubstr("scene.json: sets.p.fields.v.value[1][1]: invalid "
                        "JSON: number overflow"));
}

TEST_F(SceneTest, ValuesOutsideTheirTypeAreErrors) {
  // 3e9 would wrap to a negative int32 (cgMaxIters: no iterations at all).
  EXPECT_THAT(parseError(R"({"sets": {}, "externs": {"n": {"type": "int32",
                             "value": 3e9}}})"),
              HasSubstr("scene.json: externs.n.value: expected int32 values "
                        "from -2147483648 to 2147483647, found 3000000000"));
  EXPECT_THAT(parseError(R"({"sets": {}, "externs": {"n": {"type": "int32",
                             "value": [1, -2147483649]}}})"),
              HasSubstr("scene.json: externs.n.value: component 1: expected "
                        "int32 values"));
  auto largest = parse(R"({"sets": {}, "externs": {"n": {"type": "int32",
                          "value": [2147483647, -2147483648]}}})");
  EXPECT_TRUE(bool(largest)) << llvm::toString(largest.takeError());
  EXPECT_THAT(parseError(R"({"sets": {}, "externs": {"f": {"type": "float32",
                             "value": 1e300}}})"),
              HasSubstr("scene.json: externs.f.value: expected float32 values "
                        "from -3.402823466e+38 to 3.402823466e+38, found "
                        "1e+300"));
  EXPECT_THAT(parseError(fieldScene(R"("c": {"type": "int32",
                                              "values": [1, 2, 3, 4e10, 5]})")),
              HasSubstr("scene.json: sets.p.fields.c.values[3]: expected int32 "
                        "values"));
  EXPECT_THAT(parseError(R"({"sets": {}, "frames": 3e9, "step": "s"})"),
              HasSubstr("scene.json: frames: expected an integer of at least "
                        "0 (and at most 2147483647)"));
  EXPECT_THAT(parseError(R"({"sets": {}, "frames": 30000000000000000000,
                             "step": "s"})"),
              HasSubstr("scene.json: frames: expected an integer"));
}

TEST_F(SceneTest, DeepJsonNestingIsAnError) {
  std::string deep = R"({"sets": {}, "externs": {"g": )" +
                     std::string(100000, '[') + "1" +
                     std::string(100000, ']') + "}}";
  std::string err = parseError(deep);
  EXPECT_THAT(err, HasSubstr("scene.json: externs.g[0][0]"));
  EXPECT_THAT(err, HasSubstr(": arrays and objects nested too deeply (more "
                             "than 64 levels)"));
}

TEST_F(SceneTest, MemoryBeyondTheMachineIsAnError) {
  EXPECT_THAT(buildError(R"({"sets": {"p": {"size": 2000000000,
                             "fields": {"f": {"shape": [1000]}}}}})"),
              HasSubstr("scene.json: sets.p: scene needs 1.49e+04 GiB for "
                        "the 2000000000 elements of set \"p\" and their "
                        "fields, more than the "));
  EXPECT_THAT(buildError(R"({"sets": {"p": {"size": 1, "fields": {"f":
                             {"shape": [2147483647, 2147483647, 2147483647]}
                             }}}})"),
              HasSubstr("scene.json: sets.p: scene needs more than 2^64 bytes "
                        "for the 1 elements of set \"p\""));
  EXPECT_THAT(buildError(R"({"sets": {"c": {"size": 1},
                             "g": {"grid": [2147483647, 2147483647,
                                            2147483647, 2147483647],
                                   "endpoints": "c"}}})"),
              HasSubstr("scene.json: sets.g: scene needs more than 2^64 bytes "
                        "for the more than 2^64 elements of set \"g\""));
}

/// Lowers the address-space limit (`ulimit -v`) for the test's duration.
class AddressSpaceLimit {
public:
  explicit AddressSpaceLimit(rlim_t bytes) {
    getrlimit(RLIMIT_AS, &saved);
    struct rlimit lower = saved;
    lower.rlim_cur = std::min(bytes, saved.rlim_cur);
    setrlimit(RLIMIT_AS, &lower);
  }
  ~AddressSpaceLimit() { setrlimit(RLIMIT_AS, &saved); }

private:
  struct rlimit saved;
};

TEST_F(SceneTest, RefinementBeyondTheMemoryIsAnError) {
  // Each level multiplies the 2 tets by 8; level k is estimated at
  // 2 * 8^(k-1) * 704 bytes, more than 2 GiB first at level 8 (and more
  // than the 10 levels allowed would take years).
  AddressSpaceLimit limit(2ull << 30);
  std::string err = buildError(R"({"meshes": {"m": {"file": "pyramid.node",
                                    "refine": 10}},
                                   "sets": {"p": {"mesh": "m"}}})");
  EXPECT_THAT(err, HasSubstr("scene.json: meshes.m.refine: scene needs "));
  // Level 8 unless the test process already maps most of the 2 GiB.
  EXPECT_THAT(err, ::testing::ContainsRegex(
                       " GiB for refinement level [1-8] of the mesh, more "
                       "than the [0-9.]+ GiB available"));
}

TEST_F(SceneTest, DegenerateAndInvertedTetsAreReported) {
  // Tets 0 and 1 of the pyramid are positive; tet 2 is tet 0 reflected and
  // tet 3 repeats a vertex (volume 0).
  dir.write("bad.node", kPyramidNode);
  dir.write("bad.ele", "4 4 0\n0 0 1 2 3\n1 1 2 3 4\n2 0 2 1 3\n"
                       "3 0 1 1 3\n");
  auto scene = parse(R"({"meshes": {"m": "bad.node"},
                         "sets": {"p": {"mesh": "m"}}})");
  ASSERT_TRUE(bool(scene)) << llvm::toString(scene.takeError());
  SetRegistry registry;
  ::testing::internal::CaptureStderr();
  llvm::Error err = buildSets(*scene, registry);
  std::string warning = ::testing::internal::GetCapturedStderr();
  ASSERT_FALSE(bool(err)) << llvm::toString(std::move(err));
  EXPECT_THAT(warning, HasSubstr("scene.json: meshes.m: warning: 2 of 4 "
                                 "tetrahedra are degenerate or inverted (the "
                                 "first is tetrahedron 2, of volume "
                                 "-0.166667)"));
  // The pyramid alone draws no warning.
  auto good = parse(R"({"meshes": {"m": "pyramid.node"},
                        "sets": {"p": {"mesh": "m"}}})");
  ASSERT_TRUE(bool(good));
  SetRegistry goodRegistry;
  ::testing::internal::CaptureStderr();
  ASSERT_FALSE(bool(buildSets(*good, goodRegistry)));
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
}

} // namespace
