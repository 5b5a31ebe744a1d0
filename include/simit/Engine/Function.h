//===--- Function.h - A compiled Simit function and its bindings -*- C++ -*-===//
//
// The paper's section 5 API: a Function is compiled from a Program, its
// externs are bound to Sets and host buffers by name, init() prepares what
// the bindings need once (sparsity patterns and location tables, the
// argument descriptors), and run() calls the JIT-compiled code, which reads
// and writes the Sets' field arrays in place: nothing is copied per run.
//
//   simit::Function step = *program.compile("step");
//   step.bind("points", points);
//   step.bind("springs", springs);
//   step.bind("h", &h);
//   if (llvm::Error err = step.init()) ...
//   if (llvm::Error err = step.run()) ...
//
// A Set whose structure changes (add/remove, see Set::version) is prepared
// again by the next run(). Bound host buffers must stay alive and in place
// while the Function runs.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_ENGINE_FUNCTION_H
#define SIMIT_ENGINE_FUNCTION_H

#include "simit/Engine/HostABI.h"
#include "simit/Runtime/Set.h"

#include "llvm/ADT/ArrayRef.h"
#include "llvm/ADT/StringRef.h"
#include "llvm/Support/Error.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace simit {

class CompiledModule;

/// A value returned by a function (not through a binding): a scalar or a
/// dense tensor copied out of the returned memref.
struct HostValue {
  ScalarKind scalar = ScalarKind::Float64;
  /// Complex components: each is a (re, im) pair of `scalar`s in `bytes`.
  bool isComplex = false;
  std::vector<int64_t> shape; // empty for a scalar
  std::vector<uint8_t> bytes; // row-major, scalarSize(scalar) per number

  /// The numbers in `bytes`: the components, or twice as many (re, im
  /// pairs) for complex components.
  size_t numNumbers() const { return bytes.size() / scalarSize(scalar); }
  size_t numComponents() const { return numNumbers() / (isComplex ? 2 : 1); }
  /// Number i converted to double (bools and integers exactly); for complex
  /// components, 2k is the real and 2k + 1 the imaginary part of component k.
  double component(size_t i) const;
};

/// The error init() returns for an argument that does not fit its binding,
/// so that a caller can say where the bound value came from (a scene file's
/// JSON path). Its message is the whole description.
class ArgumentError : public llvm::ErrorInfo<ArgumentError> {
public:
  static char ID;
  ArgumentError(ArgumentBinding argument, std::string message)
      : binding(std::move(argument)), text(std::move(message)) {}
  const ArgumentBinding &argument() const { return binding; }
  void log(llvm::raw_ostream &os) const override { os << text; }
  std::error_code convertToErrorCode() const override {
    return llvm::inconvertibleErrorCode();
  }

private:
  ArgumentBinding binding;
  std::string text;
};

class Function {
public:
  Function();
  Function(Function &&);
  Function &operator=(Function &&);
  ~Function();

  llvm::StringRef name() const;
  /// What each argument of the compiled code carries.
  const HostSignature &signature() const;

  /// The names the function needs bound: sets, and extern tensors (bound
  /// with the buffer form of bind).
  std::vector<std::string> requiredSets() const;
  std::vector<std::string> requiredTensors() const;
  /// The number of the function's own parameters (bound by bindParameter).
  unsigned numParameters() const;

  /// Binds the extern set `name`. Checked against the program by init().
  llvm::Error bind(llvm::StringRef name, Set &set);
  /// Binds an extern tensor to a host buffer of components of `type`,
  /// row-major, of the given shape ({} for a scalar).
  llvm::Error bind(llvm::StringRef name, void *data, ComponentType type,
                   llvm::ArrayRef<int> shape);
  /// Binds parameter `index` (0-based, in the Simit signature's order) to a
  /// host buffer, as bind does for externs. A complex parameter of shape S
  /// is bound to a buffer of its parts' type (Float64 or Float32) of shape
  /// S followed by 2 (re, im pairs, the layout of std::complex).
  llvm::Error bindParameter(unsigned index, void *data, ComponentType type,
                            llvm::ArrayRef<int> shape);
  template <typename T>
  llvm::Error bind(llvm::StringRef name, T *data, llvm::ArrayRef<int> shape = {}) {
    return bind(name, static_cast<void *>(data), ComponentTypeOf<T>::value,
                shape);
  }

  /// Checks every binding against the program (an unbound extern, a field
  /// of another type or shape, a set of another cardinality are errors
  /// naming it, as an ArgumentError), builds the sparsity patterns the
  /// function assembles into, and packs the argument descriptors.
  llvm::Error init();
  /// Runs the function, first calling init() when it has not run or a bound
  /// set changed structure since.
  llvm::Error run();

  /// The values the last run() returned, in order.
  llvm::ArrayRef<HostValue> results() const;

  /// Scans the bound float fields and tensors for NaN or infinity; returns
  /// a description of the first ("field 'points.v' of element 7, component
  /// 1, is nan") or an empty string.
  std::string findNonFinite() const;

private:
  friend class Program;
  struct Impl;
  Function(std::shared_ptr<CompiledModule> module, const HostSignature &signature);
  std::unique_ptr<Impl> impl;
};

} // namespace simit

#endif // SIMIT_ENGINE_FUNCTION_H
