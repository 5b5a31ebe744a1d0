//===--- SceneBindings.cpp - simit.Scene ------------------------------------===//
//
// A scene (docs/scene-format.md) from a JSON file or a dict, run by the
// engine's SceneRunner as simit-run --scene runs it. Its sets and extern
// tensors read as simit.Set and NumPy arrays over the scene's own memory,
// so Python can look at (and change) the state between frames.
//
//===----------------------------------------------------------------------===//

#include "Common.h"

#include "simit/Engine/SceneRun.h"

#include <pybind11/stl.h>

#include <functional>

using namespace simit;
using namespace simit::python;

namespace {
struct PyScene {
  std::unique_ptr<SceneRunner> runner;
};
using SceneHandle = std::shared_ptr<PyScene>;

SceneDescription describe(const py::object &scene, const py::object &directory) {
  py::module_ os = py::module_::import("os");
  if (py::isinstance<py::dict>(scene)) {
    std::string text =
        py::str(py::module_::import("json").attr("dumps")(scene));
    std::string base = py::str(directory.is_none()
                                   ? os.attr("getcwd")()
                                   : os.attr("fspath")(directory));
    return check(parseScene(text, "<scene dict>", base));
  }
  if (!directory.is_none())
    throw py::type_error("directory= is for a scene given as a dict; a scene "
                         "file's paths are relative to the file");
  std::string path = py::str(os.attr("fspath")(scene));
  return check(loadScene(path));
}

py::dict timesOf(const SceneTimes &times) {
  SceneTimeSummary summary = times.summarize();
  py::dict result;
  result["compile_ms"] = summary.compileMs;
  result["bind_ms"] = summary.bindMs;
  result["sets_ms"] = summary.setsMs;
  result["init_ms"] = summary.initMs;
  result["frames"] = summary.frames;
  result["frame_ms"] = summary.frameMs;
  result["first_frame_ms"] = summary.firstFrameMs;
  result["assembly_ms"] = summary.assemblyMs;
  result["solve_ms"] = summary.solveMs;
  py::dict perFrame;
  perFrame["frame_ms"] = times.frameMs;
  perFrame["assembly_ms"] = times.assemblyMs;
  perFrame["solve_ms"] = times.solveMs;
  result["per_frame"] = perFrame;
  return result;
}

/// Runs `work` on the runner without the GIL, its sets marked in use.
void runFrames(PyScene &self,
               const std::function<llvm::Error(SceneRunner &)> &work) {
  std::vector<const Set *> sets;
  for (const auto &set : self.runner->sets().sets())
    sets.push_back(set.get());
  RunningGuard guard(sets);
  llvm::Error err = [&] {
    py::gil_scoped_release release;
    return work(*self.runner);
  }();
  std::string message = err ? llvm::toString(std::move(err)) : "";
  if (message.rfind("check-numerics: ", 0) == 0)
    throw NumericsError(message);
  if (!message.empty())
    throw SimitError(message);
}
} // namespace

void simit::python::defineScenes(py::module_ &module) {
  py::class_<PyScene, SceneHandle>(module, "Scene", R"doc(
A scene (docs/scene-format.md) ready to run: its program compiled, its sets
built and bound.

  scene = simit.Scene("examples/springs/springs-bunny.json", time=True)
  scene.run()                          # init, then the scene's frames
  x = scene.sets["points"]["x"]        # the positions, in place
  scene.times["frame_ms"]              # simit-run --time's figures

`scene` is a path or a dict of the same JSON (its relative paths resolved
against `directory`, default the current directory). Outputs are written to
`output_dir` when one is given.
)doc")
      .def(py::init([](const py::object &scene, const py::object &program,
                       const py::object &directory,
                       const py::object &outputDir, std::optional<int> frames,
                       bool float32, bool time, bool checkNumerics,
                       int threads) {
             SceneDescription description = describe(scene, directory);
             py::module_ os = py::module_::import("os");
             SceneRunOptions options;
             if (!program.is_none())
               options.programPath = py::str(os.attr("fspath")(program));
             if (!outputDir.is_none())
               options.outputDirectory =
                   std::string(py::str(os.attr("fspath")(outputDir)));
             options.frames = frames;
             options.precision =
                 float32 ? FloatPrecision::Single : FloatPrecision::Double;
             options.timePhases = time;
             options.checkNumerics = checkNumerics;
             options.threads = threads;
             // Python reads and writes the sets and externs between frames:
             // every field is built, and no value is folded into the code.
             options.skipUnusedFields = false;
             options.foldConstantExterns = false;
             options.foldUniformFields = false;
             auto runner = [&] {
               py::gil_scoped_release release;
               return SceneRunner::create(std::move(description), options);
             }();
             return std::make_shared<PyScene>(PyScene{check(std::move(runner))});
           }),
           py::arg("scene"), py::kw_only(), py::arg("program") = py::none(),
           py::arg("directory") = py::none(), py::arg("output_dir") = py::none(),
           py::arg("frames") = py::none(), py::arg("float32") = false,
           py::arg("time") = false, py::arg("check_numerics") = false,
           py::arg("threads") = 0)
      .def("init",
           [](PyScene &self) {
             runFrames(self, [](SceneRunner &r) { return r.init(); });
           },
           "Runs the init functions and writes frame 0 (once).")
      .def("step",
           [](PyScene &self, int count) {
             runFrames(self, [count](SceneRunner &r) { return r.step(count); });
           },
           py::arg("count") = 1, "Runs `count` frames (init first if needed).")
      .def("run",
           [](PyScene &self) {
             runFrames(self, [](SceneRunner &r) { return r.run(); });
             return timesOf(self.runner->times());
           },
           "Runs init and the remaining frames; returns the times.")
      .def_property_readonly("frame",
                             [](const PyScene &self) { return self.runner->frame(); })
      .def_property_readonly("frames",
                             [](const PyScene &self) { return self.runner->frames(); })
      .def_property_readonly(
          "times", [](const PyScene &self) { return timesOf(self.runner->times()); },
          "simit-run --time's figures in milliseconds: compile_ms, bind_ms, "
          "sets_ms, init_ms, and medians of frames 2..N frame_ms, "
          "assembly_ms, solve_ms (first_frame_ms apart), per_frame lists.")
      .def_property_readonly(
          "sets",
          [](const SceneHandle &self) {
            py::dict sets;
            for (const auto &set : self->runner->sets().sets())
              sets[py::str(set->name().str())] =
                  SetHandle{std::shared_ptr<Set>(self, set.get())};
            return sets;
          })
      .def_property_readonly(
          "externs",
          [](const SceneHandle &self) {
            py::dict externs;
            for (auto &[name, tensor] : self->runner->sets().externs()) {
              size_t count = 1;
              for (int dim : tensor.shape)
                count *= dim;
              // A scalar is a one-element array of shape ().
              externs[py::str(name)] =
                  viewOf(tensor.data(), tensor.type, count, {}, self)
                      .attr("reshape")(py::tuple(py::cast(tensor.shape)));
            }
            return externs;
          },
          "{name: array} over the extern tensors the program reads.")
      .def_property_readonly("written_files", [](const PyScene &self) {
        return self.runner->writtenFiles();
      });
}
