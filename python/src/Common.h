//===--- Common.h - Shared pieces of the simit Python module ----*- C++ -*-===//
//
// Errors: an llvm::Error becomes a C++ SimitError, which the module turns
// into the Python exception simit.Error (simit/errors.py parses the file,
// line and column out of its message). Component types: the NumPy dtype of
// each ComponentType. Views: NumPy arrays over a Set's field arrays share
// the Set's memory; the Set counts them, so that a change that would move
// or free that memory is refused while one is alive.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_PYTHON_COMMON_H
#define SIMIT_PYTHON_COMMON_H

#include "simit/Runtime/Set.h"

#include "llvm/Support/Error.h"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace simit::python {

namespace py = pybind11;

/// An error of the C++ API, raised in Python as simit.Error.
struct SimitError : std::runtime_error {
  using std::runtime_error::runtime_error;
};
/// An error of --check-numerics, raised as simit.NumericsError.
struct NumericsError : SimitError {
  using SimitError::SimitError;
};

/// Throws SimitError with the message of `err`, if it is an error.
void check(llvm::Error err);
template <typename T> T check(llvm::Expected<T> value) {
  if (!value)
    check(value.takeError());
  return std::move(*value);
}

py::dtype dtypeOf(ComponentType type);
/// The component type of a NumPy dtype; TypeError for any other than
/// float64, float32, int32 and bool.
ComponentType componentTypeOf(const py::dtype &dtype);

/// `value` (a number, sequence or array) as a C-contiguous array of `type`
/// (the array itself when it is one already), when every value fits: ValueError
/// for fractions or values out of range of int32, TypeError for complex values
/// of a real type. `what` names the destination in the message.
py::array convertExactly(const py::object &value, ComponentType type,
                         const std::string &what);

/// A Set as Python holds it: the pointer keeps alive whatever owns the Set
/// (the Set and its endpoint sets, or the scene it belongs to).
struct SetHandle {
  std::shared_ptr<Set> set;
};

/// A NumPy array over `count` blocks of `blockShape` components of `type`
/// at `data`, in place; it keeps `owner` alive.
py::array viewOf(void *data, ComponentType type, size_t count,
                 const std::vector<int> &blockShape,
                 std::shared_ptr<void> owner, bool writeable = true);
/// A view of field `field` of `set`, counted by the set's live views.
py::array fieldView(const std::shared_ptr<Set> &set, const std::string &field);
/// A read-only view of the endpoint array of `set`, counted likewise.
py::array endpointView(const std::shared_ptr<Set> &set);
/// Refuses (BufferError) to change `set` in a way that moves or frees
/// `field`'s array (every field when empty) while a view of it is alive,
/// and (RuntimeError) any structural change while compiled code runs on it.
void requireUnshared(const Set &set, const std::string &field = "");

/// Marks sets as in use by compiled code for the lifetime of the guard.
class RunningGuard {
public:
  explicit RunningGuard(std::vector<const Set *> sets);
  ~RunningGuard();
  RunningGuard(const RunningGuard &) = delete;
  RunningGuard &operator=(const RunningGuard &) = delete;

private:
  std::vector<const Set *> sets;
};

void defineSets(py::module_ &module);
void defineMeshes(py::module_ &module);
void definePrograms(py::module_ &module);
void defineScenes(py::module_ &module);

} // namespace simit::python

#endif // SIMIT_PYTHON_COMMON_H
