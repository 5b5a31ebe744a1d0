//===--- ObjectCodegen.h - LLVM IR to objects, on several cores -*- C++ -*-===//
//
// LLVM's -O3 and code generation take most of a cold compile and work
// function by function. A large module is cut into partitions of about
// equal size, one per core (at most four), each optimised and compiled on a
// thread of its own in an LLVMContext of its own; the JIT links their
// objects together. Cutting only stops inlining across partitions, and the
// program's functions are inlined long before (simit-inline-functions): the
// code's arithmetic, and so every result, is the same for any number of
// partitions.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_LIB_ENGINE_OBJECTCODEGEN_H
#define SIMIT_LIB_ENGINE_OBJECTCODEGEN_H

#include "simit/Engine/Program.h"

#include "llvm/ExecutionEngine/Orc/JITTargetMachineBuilder.h"
#include "llvm/IR/Module.h"
#include "llvm/Support/Error.h"

#include <string>
#include <vector>

namespace simit {

/// Optimises `module` at -O3 and compiles it for `target` into relocatable
/// objects, one per partition (`module` is left externalised, not to be
/// compiled again). `partitions`: how many (at most one per function
/// definition); 0 chooses one per core, at most four, and fewer for a small
/// module. Adds the wall times of both steps to `times`.
llvm::Expected<std::vector<std::string>>
compileToObjects(llvm::Module &module,
                 const llvm::orc::JITTargetMachineBuilder &target,
                 unsigned partitions, CompileTimes &times);

} // namespace simit

#endif // SIMIT_LIB_ENGINE_OBJECTCODEGEN_H
