//===--- Module.cpp - The simit._simit extension module ---------------------===//
//
// The compiled half of the `simit` Python package (python/simit/__init__.py
// is the other): Set, Mesh, Program, Function and Scene over the C++ API.
// C++ errors become the package's exception classes of simit/errors.py.
//
//===----------------------------------------------------------------------===//

#include "Common.h"

using namespace simit::python;

PYBIND11_MODULE(_simit, module) {
  module.doc() = "The C++ half of the simit package.";
  py::module_ errors = py::module_::import("simit.errors");
  // Held for the life of the process, as the translator may run any time.
  static py::handle errorType = py::object(errors.attr("Error")).release();
  static py::handle numericsErrorType =
      py::object(errors.attr("NumericsError")).release();
  py::register_exception_translator([](std::exception_ptr pending) {
    try {
      if (pending)
        std::rethrow_exception(pending);
    } catch (const NumericsError &err) {
      PyErr_SetString(numericsErrorType.ptr(), err.what());
    } catch (const SimitError &err) {
      PyErr_SetString(errorType.ptr(), err.what());
    }
  });
  defineSets(module);
  defineMeshes(module);
  definePrograms(module);
  defineScenes(module);
}
