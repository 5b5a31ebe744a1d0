//===--- Program.h - Loading and compiling Simit programs -------*- C++ -*-===//
//
// The paper's section 5 API: a Program holds one Simit program (a .sim
// source, or MLIR in the simit dialect or already lowered to loops) and
// compiles its exported functions: frontend -> simit dialect -> simit passes
// -> loops over sets -> LLVM dialect -> LLVM at -O3 -> an object linked into
// an ORC JIT. With a cache directory, the object is kept on disk and a later
// Program with the same source and options loads it instead of compiling.
//
//   simit::Program program;
//   if (llvm::Error err = program.loadFile("springs.sim")) ...
//   llvm::Expected<simit::Function> step = program.compile("step");
//
// The whole module is compiled once, by the first compile(); later calls
// share the machine code.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_ENGINE_PROGRAM_H
#define SIMIT_ENGINE_PROGRAM_H

#include "simit/Engine/Function.h"
#include "simit/Runtime/SolveSession.h"

#include "llvm/ADT/StringRef.h"
#include "llvm/Support/Error.h"

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace simit {

/// The precision of Simit's `float` (language.md 4.1): a whole-program
/// setting that also fixes the type of bound float fields and externs.
enum class FloatPrecision { Double, Single };

/// Where the set loops of exported functions run: on the host CPU, or as
/// CUDA kernels on the process's first NVIDIA GPU (docs/gpu.md).
enum class Target { CPU, GPU };

/// What the host promises about the runs of a program, so that the
/// compiler can skip what they do not need (docs/scene-specialisation.md).
/// Every part is in the compile cache's key.
struct ProgramSpecialisation {
  /// The exported functions the host will call: the others are not
  /// compiled (compile() of one is an unknown function). Empty: all.
  std::vector<std::string> entryFunctions;
  /// Extern tensors that keep these components (row-major; bools and
  /// integers exactly) while the program runs: read as constants, and not
  /// bound, by functions that do not write them.
  std::map<std::string, std::vector<double>> constantExterns;
  /// Fields with one value (one block, row-major) over their whole set,
  /// by set and field: read as constants by element functions that only
  /// ever see that set, unless a function writes the field.
  std::map<std::string, std::map<std::string, std::vector<double>>>
      uniformFields;
};

struct ProgramOptions {
  FloatPrecision precision = FloatPrecision::Double;
  /// Functions of a .sim program to compile with a host ABI although they
  /// are not `export`ed: the functions `%!` assertions and --eval call.
  std::vector<std::string> hostFunctions;
  /// Bracket assemblies and solves with the phase timer (simit-time-phases;
  /// simit::readPhaseTimes() in simit/ABI/RuntimeFunctions.h reads it).
  bool timePhases = false;
  /// Scan the results of assemblies and solves for NaN and infinity
  /// (simit-check-numerics; simit::takeNumericsProblem() in
  /// simit/ABI/RuntimeFunctions.h reads the first one). Off, nothing is
  /// scanned.
  bool checkNumerics = false;
  /// Threads that run the set loops (docs/threads.md): 0 takes
  /// $SIMIT_NUM_THREADS when set, else every core (resolveThreadCount()).
  /// With one thread the code has no parallel regions; the results are the
  /// same, bit for bit, for every number of threads.
  int threads = 0;
  /// Where compiled programs are kept between runs, keyed by the compiler,
  /// the host CPU, the source and the options above (each option that
  /// changes the code must be part of the key, Program.cpp); empty: every
  /// Program compiles. defaultCompileCacheDirectory() is the usual place.
  std::string cacheDirectory;
  /// How `x = A \ b` and chol/lu on system matrices solve (docs/solvers.md).
  /// Read at run time, not compiled in: Program::solver() changes it
  /// between runs without a recompile.
  SolveSettings solver;
  /// Solve `(A + u v^T) \ b` by Sherman–Morrison (simit-sherman-morrison);
  /// off, A + u v^T is formed and solved as it is.
  bool shermanMorrison = true;
  /// Map and assembly results nothing uses are not computed
  /// (simit-eliminate-dead-assemblies).
  bool eliminateDeadAssemblies = true;
  /// Element kernels run on as many elements at once as the host's vectors
  /// hold (simit-vectorize-element-loops); off, one element at a time. The
  /// results are the same.
  bool vectorizeElements = true;
  /// What the runs need, when the host knows (SceneRunner does).
  ProgramSpecialisation specialisation;
  /// Shared libraries that define the C functions of the program's
  /// `extern func`s (docs/lowering.md, "Host functions"), loaded into the
  /// process when the Program is made.
  std::vector<std::string> hostLibraries;
  /// With Target::GPU, compile() compiles through simit-gpu-pipeline for
  /// the compute capability of the device (cuda::defaultDevice()), and
  /// fails with "no CUDA device: <reason>" before lowering when there is
  /// none. emit() needs no device (it lowers for sm_90).
  Target target = Target::CPU;
};

/// A field that the elements of an extern set declare: its name and the
/// host type of its array over the set (memref<?x3xf64>), as a function
/// that uses the field binds it; not a memref (ValueType::isMemRef) when
/// the runtime has no arrays of its component type (i16 in hand-written
/// IR).
struct DeclaredField {
  std::string name;
  ValueType type;
};
/// The declared fields of each extern set, by set name.
using DeclaredFields = std::map<std::string, std::vector<DeclaredField>>;

/// The number of threads `requested` stands for: itself when positive;
/// when 0, $SIMIT_NUM_THREADS when it is set (it must be a positive
/// integer), else the number of cores this process may run on. A negative
/// number, or a malformed variable, is an error naming it.
llvm::Expected<int> resolveThreadCount(int requested);

/// "cpu" or "gpu".
llvm::StringRef targetName(Target target);

/// $XDG_CACHE_HOME/simit, else $HOME/.cache/simit; empty when neither
/// variable is set.
std::string defaultCompileCacheDirectory();

/// Where the time of compile() went, in milliseconds.
struct CompileTimes {
  /// The code came from the cache: nothing was lowered or compiled.
  bool cached = false;
  /// The MLIR pipeline down to the LLVM dialect.
  double loweringMs = 0;
  /// Translation to LLVM IR and LLVM's -O3 passes.
  double optimizationMs = 0;
  /// Machine code for the host CPU.
  double codegenMs = 0;
  /// Reading the cache (when used) and linking the object into the JIT.
  double loadMs = 0;
};

/// Where --emit stops: the simit dialect as imported, the loops over sets
/// (after convert-simit-to-loops), or the LLVM dialect handed to the JIT.
enum class Stage { Simit, Loops, LLVM };

class Program {
public:
  explicit Program(ProgramOptions options = {});
  Program(Program &&);
  Program &operator=(Program &&);
  ~Program();

  /// Loads a .sim file, or an .mlir file of simit or lowered IR.
  llvm::Error loadFile(llvm::StringRef path);
  /// Loads Simit source; `bufferName` names it in diagnostics.
  llvm::Error loadString(llvm::StringRef source,
                         llvm::StringRef bufferName = "<string>");
  /// Loads MLIR text (simit dialect, or loops with simit.bindings).
  llvm::Error loadMLIR(llvm::StringRef text,
                       llvm::StringRef bufferName = "<mlir>");

  /// The IR at `stage` as text.
  llvm::Expected<std::string> emit(Stage stage);

  /// Compiles the module (once) and returns exported function `name`; an
  /// unknown name is an error listing the exported functions.
  llvm::Expected<Function> compile(llvm::StringRef name);

  /// The exported functions of the compiled module, sorted by name.
  llvm::Expected<std::vector<std::string>> exportedFunctions();

  /// The solver of this program's solves: its settings, its factorisation
  /// cache, and its statistics per solve statement. Shared by every
  /// Function the program compiles.
  SolveSession &solver();

  /// Where the first compile() spent its time (all zero before it).
  const CompileTimes &compileTimes() const;

  /// The fields the element type of each extern set declares, by set name
  /// (empty when the loaded IR has no simit.extern sets, e.g. loops IR).
  llvm::Expected<DeclaredFields> externSetFields();

  /// The endpoint sets the program declares for each extern set, by set
  /// name, one per endpoint position (none for a vertex set; a grid's point
  /// set at both of its edges' ends).
  llvm::Expected<std::map<std::string, std::vector<std::string>>>
  externSetEndpoints();

  /// The names of the program's extern tensors (`extern h : float;`,
  /// extern vectors over sets included), sorted.
  llvm::Expected<std::vector<std::string>> externTensorNames();

private:
  struct Impl;
  std::unique_ptr<Impl> impl;
};

} // namespace simit

#endif // SIMIT_ENGINE_PROGRAM_H
