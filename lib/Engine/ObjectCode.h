//===--- ObjectCode.h - Compiled code before it is loaded -----------------===//
//
// A lowered module compiled for the host: relocatable objects that define
// the packed entry point `_mlir_<name>(void **args)` of every exported
// function, and the host ABI of each. Program compiles it (Lowering.h) or
// reads it back from the compile cache (CompileCache.h), then loads it into
// a JIT.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_LIB_ENGINE_OBJECTCODE_H
#define SIMIT_LIB_ENGINE_OBJECTCODE_H

#include "CompiledModule.h"

#include "simit/Engine/Program.h"

#include "llvm/ExecutionEngine/Orc/JITTargetMachineBuilder.h"
#include "llvm/Support/Error.h"

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace simit {

struct ObjectCode {
  /// Names per set, by set name.
  using SetNames = std::map<std::string, std::vector<std::string>>;

  /// The host ABI and memref convention of every exported function (their
  /// entry points are unset until loaded).
  llvm::StringMap<CompiledFunction> functions;
  /// The data layout the object was compiled for (the JIT mangles symbol
  /// names with it).
  std::string dataLayout;
  /// The relocatable object files, one per partition of the module
  /// (ObjectCodegen.h), which refer to one another's symbols.
  std::vector<std::string> objects;
  /// The fields of each extern set's elements, by set
  /// (Program::externSetFields()), so that a program loaded from the cache
  /// need not be imported.
  DeclaredFields externSetFields;
  /// The endpoint sets of each extern set, one per endpoint position
  /// (Program::externSetEndpoints()).
  SetNames externSetEndpoints;
  /// The names of the program's extern tensors, sorted
  /// (Program::externTensorNames()).
  std::vector<std::string> externTensors;
};

/// The host CPU with all its features, at -O3, with the small code model and
/// position-independent code that the JIT's linker (JITLink) expects.
llvm::Expected<llvm::orc::JITTargetMachineBuilder> hostTarget();

/// The width in bits of the host's widest vector registers that LLVM uses:
/// 512 with AVX-512, 256 with AVX, else 128 (SSE2, NEON).
unsigned hostVectorBits();

/// Links `code` into a new JIT that resolves the runtime functions and the
/// process's own symbols (libc, libm), and looks up every entry point.
llvm::Expected<std::shared_ptr<CompiledModule>>
loadObjectCode(const ObjectCode &code);

/// `code` as bytes, and back; deserializing checks every length against
/// what is left, so truncated or altered bytes are an error, not a crash.
std::string serializeObjectCode(const ObjectCode &code);
llvm::Expected<ObjectCode> deserializeObjectCode(llvm::StringRef bytes);

} // namespace simit

#endif // SIMIT_LIB_ENGINE_OBJECTCODE_H
