//===--- ProgramBindings.cpp - simit.Program and simit.Function -------------===//
//
// A Program loads and compiles Simit source; a Function is one of its
// exported functions. Sets are bound by reference; an extern tensor is bound
// to a NumPy array in place when the array has the extern's component type
// and is contiguous (so the array and the program share it), or to a fresh
// array made from a Python value. Compiled code runs without the GIL.
//
//===----------------------------------------------------------------------===//

#include "Common.h"

#include "simit/Engine/Program.h"
#include "simit/ABI/RuntimeFunctions.h"
#include "simit/Runtime/SolveSession.h"

#include <pybind11/stl.h>

#include <algorithm>
#include <cstring>
#include <map>

using namespace simit;
using namespace simit::python;

namespace {
struct PyFunction {
  std::string name;
  Function function;
  bool checkNumerics = false;
  /// What is bound by name, kept alive: a Set, or the NumPy array of an
  /// extern tensor.
  std::map<std::string, py::object> bound;
  /// The arrays bound to the parameters of the last call.
  std::vector<py::array> parameters;
  bool running = false;
};

struct PyProgram {
  ProgramOptions options;
  Program program;
  std::map<std::string, std::shared_ptr<PyFunction>> functions;
  explicit PyProgram(ProgramOptions options)
      : options(options), program(options) {}
};

const ArgumentBinding *findArgument(const Function &function,
                                    ArgumentBinding::Kind kind,
                                    const std::string &name, int64_t index) {
  for (const ArgumentBinding &arg : function.signature().arguments)
    if (arg.kind == kind && (kind == ArgumentBinding::Kind::Parameter
                                 ? arg.index == index
                                 : arg.name == name))
      return &arg;
  return nullptr;
}

ComponentType argumentType(const ArgumentBinding &arg) {
  ComponentType type;
  if (!componentTypeFor(arg.type.scalar, type))
    throw py::type_error(arg.describe() + " is of type " + arg.type.str() +
                         ", which Python cannot pass");
  return type;
}

std::vector<int> shapeOf(const py::array &array) {
  return std::vector<int>(array.shape(), array.shape() + array.ndim());
}

/// An extern's array: `value` itself when it is an ndarray of the extern's
/// component type laid out contiguously (shared with the program), else a
/// new array of that type made from a Python number or sequence.
py::array externArray(const ArgumentBinding &arg, const py::object &value) {
  py::dtype dtype = dtypeOf(argumentType(arg));
  if (py::isinstance<py::array>(value)) {
    py::array array = py::reinterpret_borrow<py::array>(value);
    if (!array.dtype().equal(dtype))
      throw py::type_error(arg.describe() + " holds " +
                           std::string(py::str(py::handle(dtype))) +
                           " components; an array of " +
                           std::string(py::str(py::handle(array.dtype()))) +
                           " would have to be copied, and the program would "
                           "not share it (convert it with .astype first)");
    if (!(array.flags() & py::array::c_style) || !array.writeable())
      throw py::type_error(arg.describe() +
                           ": expected a writeable C-contiguous array");
    return array;
  }
  return convertExactly(value, argumentType(arg), arg.describe());
}

/// Binds `value` to the set or extern `name`; returns what is bound (the
/// set, or the extern's array).
py::object bindValue(PyFunction &self, const std::string &name,
                     const py::object &value) {
  if (py::isinstance<SetHandle>(value)) {
    if (findArgument(self.function, ArgumentBinding::Kind::Extern, name, -1))
      throw py::type_error("function '" + self.name + "': '" + name +
                           "' is an extern tensor; bind an array to it");
    check(self.function.bind(name, *value.cast<SetHandle &>().set));
    self.bound[name] = value;
    return value;
  }
  const ArgumentBinding *arg =
      findArgument(self.function, ArgumentBinding::Kind::Extern, name, -1);
  std::vector<std::string> sets = self.function.requiredSets();
  if (std::find(sets.begin(), sets.end(), name) != sets.end())
    throw py::type_error("function '" + self.name + "': '" + name +
                         "' is an extern set; bind a simit.Set to it");
  if (!arg) {
    // Let the engine name what the function does use.
    check(self.function.bind(name, nullptr, ComponentType::Float64, {}));
    return value;
  }
  py::array array = externArray(*arg, value);
  check(self.function.bind(name, array.mutable_data(), argumentType(*arg),
                           shapeOf(array)));
  self.bound[name] = array;
  return array;
}

bool uses(const PyFunction &function, const std::string &name) {
  for (const auto &names :
       {function.function.requiredSets(), function.function.requiredTensors()})
    if (std::find(names.begin(), names.end(), name) != names.end())
      return true;
  return false;
}

void bindParameters(PyFunction &self, const py::args &args) {
  if (args.size() != self.function.numParameters())
    throw py::type_error("function '" + self.name + "' takes " +
                         std::to_string(self.function.numParameters()) +
                         " arguments, not " + std::to_string(args.size()));
  py::module_ numpy = py::module_::import("numpy");
  self.parameters.clear();
  for (size_t i = 0; i < args.size(); ++i) {
    const ArgumentBinding *arg = findArgument(
        self.function, ArgumentBinding::Kind::Parameter, "", static_cast<int64_t>(i));
    if (!arg)
      throw py::type_error("function '" + self.name + "': parameter " +
                           std::to_string(i) + " is not used");
    ComponentType type = argumentType(*arg);
    py::array array;
    if (arg->type.isComplex) {
      // (re, im) pairs of the part type: the layout of std::complex.
      py::dtype complexType(type == ComponentType::Float32 ? "complex64"
                                                           : "complex128");
      py::array values(
          numpy.attr("asarray")(args[i], complexType, py::arg("order") = "C"));
      // Flat first: NumPy views a 0-d array only as a dtype of its size.
      array =
          py::array(values.attr("reshape")(-1)
                        .attr("view")(dtypeOf(type))
                        .attr("reshape")(py::tuple(py::cast(shapeOf(values))) +
                                         py::make_tuple(2)));
    } else {
      array = convertExactly(args[i], type,
                             "function '" + self.name + "': parameter " +
                                 std::to_string(i));
    }
    check(self.function.bindParameter(static_cast<unsigned>(i),
                                      array.mutable_data(), type,
                                      shapeOf(array)));
    self.parameters.push_back(array);
  }
}

py::object toPython(const HostValue &value) {
  if (value.scalar == ScalarKind::String) {
    const char *text;
    std::memcpy(&text, value.bytes.data(), sizeof text);
    return py::str(text ? text : "");
  }
  const char *dtypes[] = {"float64", "float32", "int32", "int64",
                          "int64",   "bool"};
  py::dtype dtype(dtypes[static_cast<int>(value.scalar)]);
  std::vector<py::ssize_t> shape(value.shape.begin(), value.shape.end());
  if (value.isComplex)
    shape.push_back(2);
  py::array array(dtype, shape);
  std::memcpy(array.mutable_data(), value.bytes.data(), value.bytes.size());
  py::object result = array;
  if (value.isComplex)
    result = array.attr("view")(value.scalar == ScalarKind::Float32
                                    ? "complex64"
                                    : "complex128")
                 .attr("reshape")(py::tuple(py::cast(value.shape)));
  return value.shape.empty() ? result.attr("item")() : result;
}

py::object call(PyFunction &self, const py::args &args) {
  if (self.running)
    throw std::runtime_error("function '" + self.name + "' is already running");
  bindParameters(self, args);
  std::vector<const Set *> sets;
  for (auto &[name, value] : self.bound)
    if (py::isinstance<SetHandle>(value))
      sets.push_back(value.cast<SetHandle &>().set.get());
  {
    RunningGuard guard(sets);
    self.running = true;
    llvm::Error err = [&] {
      py::gil_scoped_release release;
      return self.function.run();
    }();
    self.running = false;
    // An assembly's NaN that a later statement tripped over (a solve of a
    // NaN right-hand side) is the cause: it is named first.
    if (err && self.checkNumerics)
      if (std::optional<std::string> problem = takeNumericsProblem())
        throw NumericsError("check-numerics: function '" + self.name +
                            "': " + *problem + "; then " +
                            llvm::toString(std::move(err)));
    check(std::move(err));
  }
  if (self.checkNumerics) {
    if (std::optional<std::string> problem = takeNumericsProblem())
      throw NumericsError("check-numerics: function '" + self.name +
                          "': " + *problem);
    std::string problem = self.function.findNonFinite();
    if (!problem.empty())
      throw NumericsError("check-numerics: after function '" + self.name +
                          "': " + problem);
  }
  llvm::ArrayRef<HostValue> results = self.function.results();
  if (results.empty())
    return py::none();
  if (results.size() == 1)
    return toPython(results.front());
  py::tuple tuple(results.size());
  for (size_t i = 0; i < results.size(); ++i)
    tuple[i] = toPython(results[i]);
  return tuple;
}

std::shared_ptr<PyFunction> compile(PyProgram &self, const std::string &name) {
  auto cached = self.functions.find(name);
  if (cached != self.functions.end())
    return cached->second;
  llvm::Expected<Function> function = [&] {
    py::gil_scoped_release release;
    return self.program.compile(name);
  }();
  auto result = std::make_shared<PyFunction>();
  result->name = name;
  result->function = check(std::move(function));
  result->checkNumerics = self.options.checkNumerics;
  self.functions[name] = result;
  return result;
}

/// Binds each name to every exported function that uses it, one array
/// shared by them all for an extern tensor.
void bindAll(PyProgram &self, const py::kwargs &kwargs) {
  std::vector<std::shared_ptr<PyFunction>> functions;
  for (const std::string &name : check(self.program.exportedFunctions()))
    functions.push_back(compile(self, name));
  for (auto [key, value] : kwargs) {
    std::string name = py::str(key);
    py::object bound = py::reinterpret_borrow<py::object>(value);
    bool used = false;
    for (const std::shared_ptr<PyFunction> &function : functions) {
      if (!uses(*function, name))
        continue;
      bound = bindValue(*function, name, bound);
      used = true;
    }
    if (!used)
      throw py::type_error("no exported function of the program uses '" +
                           name + "'");
  }
}

py::dict externTypes(const Function &function) {
  py::dict externs;
  for (const ArgumentBinding &arg : function.signature().arguments) {
    if (arg.kind != ArgumentBinding::Kind::Extern)
      continue;
    ComponentType type;
    py::object dtype = componentTypeFor(arg.type.scalar, type)
                           ? py::object(dtypeOf(type))
                           : py::none();
    externs[py::str(arg.name)] =
        py::make_tuple(dtype, py::tuple(py::cast(arg.type.shape)));
  }
  return externs;
}
} // namespace

void simit::python::definePrograms(py::module_ &module) {
  py::class_<PyFunction, std::shared_ptr<PyFunction>>(module, "Function", R"doc(
An exported function of a compiled Program. Bind its extern sets and tensors
with bind(name=value, ...), then call it with its own parameters:

  step.bind(points=points, springs=springs, h=0.01)
  step()
)doc")
      .def_property_readonly("name", [](const PyFunction &f) { return f.name; })
      .def_property_readonly("sets",
                             [](const PyFunction &f) { return f.function.requiredSets(); },
                             "The extern sets it uses.")
      .def_property_readonly("externs",
                             [](const PyFunction &f) { return externTypes(f.function); },
                             "{name: (dtype, shape)} of the extern tensors it uses "
                             "(-1 for a dimension the binding gives).")
      .def_property_readonly("num_parameters", [](const PyFunction &f) {
        return f.function.numParameters();
      })
      .def(
          "bind",
          [](PyFunction &self, const py::kwargs &kwargs) {
            for (auto [name, value] : kwargs)
              bindValue(self, py::str(name), py::reinterpret_borrow<py::object>(value));
          },
          "Binds extern sets (simit.Set) and tensors (arrays shared in place "
          "when of the right dtype and contiguous, else numbers copied) by name.")
      .def("__getitem__",
           [](const PyFunction &self, const std::string &name) {
             auto it = self.bound.find(name);
             if (it == self.bound.end())
               throw py::key_error("nothing is bound to '" + name + "'");
             return it->second;
           })
      .def("init", [](PyFunction &self) { check(self.function.init()); },
           "Checks the bindings and prepares the call (the first call does "
           "it otherwise).")
      .def("__call__", &call)
      .def("find_non_finite",
           [](const PyFunction &self) { return self.function.findNonFinite(); })
      .def("__repr__", [](const PyFunction &self) {
        return "<simit.Function '" + self.name + "'>";
      });

  py::class_<PyProgram, std::shared_ptr<PyProgram>>(module, "Program", R"doc(
A Simit program (simit.compile makes one). Its exported functions are
compiled on first use: program.step, program["step"]. program.bind(...)
binds externs for all of them at once.
)doc")
      .def(py::init([](bool float32, bool time, bool checkNumerics,
                       std::vector<std::string> hostFunctions, int threads,
                       const std::string &target) {
             ProgramOptions options;
             // Refused here, as simit.Scene refuses it, not at the first
             // call.
             check(resolveThreadCount(threads));
             options.threads = threads;
             if (target != "cpu" && target != "gpu")
               throw py::value_error("target must be 'cpu' or 'gpu', not '" +
                                     target + "'");
             options.target = target == "gpu" ? Target::GPU : Target::CPU;
             options.precision =
                 float32 ? FloatPrecision::Single : FloatPrecision::Double;
             options.timePhases = time;
             options.checkNumerics = checkNumerics;
             options.hostFunctions = std::move(hostFunctions);
             return std::make_shared<PyProgram>(options);
           }),
           py::kw_only(), py::arg("float32") = false, py::arg("time") = false,
           py::arg("check_numerics") = false,
           py::arg("host_functions") = std::vector<std::string>{},
           py::arg("threads") = 0, py::arg("target") = "cpu")
      .def(
          "set_solver",
          [](PyProgram &self, const std::string &method,
             std::optional<double> tol, std::optional<int64_t> maxIters,
             bool strict, bool warmStart,
             std::optional<int64_t> refactorIters) {
            std::optional<SolveMethod> parsed = parseSolveMethod(method);
            if (!parsed)
              throw py::value_error("the solver method must be one of " +
                                    solveMethodNames().str() + ", not '" +
                                    method + "'");
            SolveSettings settings{*parsed,  tol,       maxIters,
                                   strict,   warmStart, refactorIters};
            if (llvm::Error err = checkSolveSettings(settings, "set_solver"))
              throw py::value_error(llvm::toString(std::move(err)));
            self.program.solver().setSettings(settings);
          },
          R"doc(How `x = A \ b` and chol/lu on system matrices solve from the
next call on (docs/solvers.md): method auto, cg, pcg-jacobi,
pcg-block-jacobi, pcg-cholesky, cholesky, ldlt or lu; tol and max_iters for
the iterative methods; strict makes a solve stopped by the cap an error;
warm_start starts iterative solves from the statement's previous answer;
refactor_iters is the iterations after which a pcg-cholesky solve
factorises its own matrix.)doc",
          py::arg("method"), py::kw_only(), py::arg("tol") = py::none(),
          py::arg("max_iters") = py::none(), py::arg("strict") = false,
          py::arg("warm_start") = true, py::arg("refactor_iters") = py::none())
      .def(
          "solver_stats",
          [](PyProgram &self) {
            py::list statements;
            for (const SolveStatementStats &stats :
                 self.program.solver().statistics()) {
              py::list methods;
              for (SolveMethod method : stats.methods)
                methods.append(solveMethodName(method).str());
              py::dict entry;
              entry["statement"] = stats.statement;
              entry["methods"] = methods;
              entry["solves"] = stats.solves;
              entry["iterations"] = stats.iterations;
              entry["max_iterations"] = stats.maxIterations;
              entry["not_converged"] = stats.notConverged;
              entry["failed"] = stats.failed;
              entry["last_relative_residual"] = stats.lastRelativeResidual;
              entry["max_relative_residual"] = stats.maxRelativeResidual;
              entry["analyses"] = stats.analyses;
              entry["factorisations"] = stats.factorisations;
              entry["reuses"] = stats.reuses;
              statements.append(entry);
            }
            return statements;
          },
          "Per solve statement: the methods, solves, iterations, residuals "
          "and factorisations so far (simit-run --stats)")
      .def("load_file",
           [](PyProgram &self, const py::object &path) {
             std::string file =
                 py::str(py::module_::import("os").attr("fspath")(path));
             check(self.program.loadFile(file));
           })
      .def(
          "load_string",
          [](PyProgram &self, const std::string &source,
             const std::string &name) {
            check(self.program.loadString(source, name));
          },
          py::arg("source"), py::arg("name") = "<string>")
      .def(
          "load_mlir",
          [](PyProgram &self, const std::string &text,
             const std::string &name) {
            check(self.program.loadMLIR(text, name));
          },
          py::arg("text"), py::arg("name") = "<mlir>")
      .def(
          "emit",
          [](PyProgram &self, const std::string &stage) {
            Stage value = stage == "simit"   ? Stage::Simit
                          : stage == "loops" ? Stage::Loops
                          : stage == "llvm"
                              ? Stage::LLVM
                              : throw py::value_error(
                                    "emit: stage is 'simit', 'loops' or "
                                    "'llvm', not '" +
                                    stage + "'");
            return check(self.program.emit(value));
          },
          py::arg("stage") = "simit", "The program's IR at a stage, as text.")
      .def_property_readonly(
          "functions",
          [](PyProgram &self) {
            return check(self.program.exportedFunctions());
          },
          "The names of the exported functions.")
      .def_property_readonly(
          "extern_set_fields",
          [](PyProgram &self) {
            std::map<std::string, std::vector<std::string>> names;
            for (const auto &[set, fields] :
                 check(self.program.externSetFields()))
              for (const DeclaredField &field : fields)
                names[set].push_back(field.name);
            return names;
          },
          "The field names of each extern set's "
          "elements, by set name.")
      .def("bind", &bindAll,
           "Binds extern sets and tensors by name, as Function.bind does, to "
           "every exported function that uses them (an extern tensor's "
           "array is the same for all).")
      .def("function", &compile, py::arg("name"))
      .def("__getitem__", &compile)
      .def("__getattr__", [](PyProgram &self, const std::string &name) {
        std::vector<std::string> names = check(self.program.exportedFunctions());
        if (std::find(names.begin(), names.end(), name) == names.end())
          throw py::attribute_error("the program exports no function '" +
                                    name + "'");
        return compile(self, name);
      });

  module.def(
      "phase_times",
      [] {
        PhaseTimes times = readPhaseTimes();
        py::dict result;
        result["assembly_ms"] = times.assemblyMs;
        result["solve_ms"] = times.solveMs;
        return result;
      },
      "Milliseconds in assemblies and solves of programs compiled with "
      "time=True, since reset_phase_times().");
  module.def("reset_phase_times", &resetPhaseTimes);
}
