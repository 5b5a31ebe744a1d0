//===--- Lowering.cpp - From the simit dialect to JIT-compiled code -------===//

#include "Lowering.h"

#include "ObjectCodegen.h"
#include "Stopwatch.h"

#include "simit/ABI/RuntimeFunctionNames.h"
#include "simit/Dialect/Simit/IR/Simit.h"
#include "simit/Dialect/Simit/Transforms/Passes.h"

#include "mlir/Dialect/Affine/IR/AffineOps.h"
#include "mlir/Dialect/Arith/IR/Arith.h"
#include "mlir/Dialect/Complex/IR/Complex.h"
#include "mlir/Dialect/ControlFlow/IR/ControlFlow.h"
#include "mlir/Dialect/Func/IR/FuncOps.h"
#include "mlir/Dialect/GPU/IR/GPUDialect.h"
#include "mlir/Dialect/Index/IR/IndexDialect.h"
#include "mlir/Dialect/LLVMIR/LLVMDialect.h"
#include "mlir/Dialect/Math/IR/Math.h"
#include "mlir/Dialect/MemRef/IR/MemRef.h"
#include "mlir/Dialect/OpenMP/OpenMPDialect.h"
#include "mlir/Dialect/SCF/IR/SCF.h"
#include "mlir/Dialect/Tensor/IR/Tensor.h"
#include "mlir/Dialect/Vector/IR/VectorOps.h"
#include "mlir/ExecutionEngine/ExecutionEngine.h"
#include "mlir/IR/Diagnostics.h"
#include "mlir/IR/Verifier.h"
#include "mlir/Pass/PassInstrumentation.h"
#include "mlir/Pass/PassManager.h"
#include "mlir/Target/LLVMIR/Dialect/Builtin/BuiltinToLLVMIRTranslation.h"
#include "mlir/Target/LLVMIR/Dialect/GPU/GPUToLLVMIRTranslation.h"
#include "mlir/Target/LLVMIR/Dialect/LLVMIR/LLVMToLLVMIRTranslation.h"
#include "mlir/Target/LLVMIR/Dialect/OpenMP/OpenMPToLLVMIRTranslation.h"
#include "mlir/Target/LLVMIR/Export.h"

#include "llvm/IR/Constants.h"
#include "llvm/IR/IRBuilder.h"
#include "llvm/IR/Module.h"
#include "llvm/Support/raw_ostream.h"
#include "llvm/Target/TargetMachine.h"

using namespace simit;

/// The pass whose output is the "loops" stage of --emit.
static constexpr llvm::StringLiteral kLoopsPass = "convert-simit-to-loops";

void simit::registerEngineDialects(mlir::DialectRegistry &registry) {
  registry.insert<mlir::simit::SimitDialect, mlir::func::FuncDialect,
                  mlir::arith::ArithDialect, mlir::math::MathDialect,
                  mlir::scf::SCFDialect, mlir::tensor::TensorDialect,
                  mlir::memref::MemRefDialect, mlir::complex::ComplexDialect,
                  mlir::affine::AffineDialect, mlir::cf::ControlFlowDialect,
                  mlir::index::IndexDialect, mlir::LLVM::LLVMDialect,
                  mlir::vector::VectorDialect, mlir::omp::OpenMPDialect>();
  mlir::simit::registerSimitInlinerInterface(registry);
  mlir::registerBuiltinDialectTranslation(registry);
  mlir::registerLLVMDialectTranslation(registry);
  mlir::registerOpenMPDialectTranslation(registry);
  // Target::GPU: the host module keeps gpu.binary and gpu.launch_func,
  // which translate to the kernels' PTX and mgpu* calls.
  registry.insert<mlir::gpu::GPUDialect>();
  mlir::registerGPUDialectTranslation(registry);
}

namespace {
/// Keeps the IR right after convert-simit-to-loops, the "loops" stage of
/// --emit.
class LoopsStageKeeper : public mlir::PassInstrumentation {
public:
  explicit LoopsStageKeeper(std::string &text) : text(text) {}
  void runAfterPass(mlir::Pass *pass, mlir::Operation *op) override {
    if (pass->getArgument() != kLoopsPass)
      return;
    llvm::raw_string_ostream os(text);
    op->print(os);
  }

private:
  std::string &text;
};
} // namespace

/// `file:line:col` of the first source position in `loc` (the .sim
/// position the frontend gave the op), else MLIR's own spelling.
static std::string describeLocation(mlir::Location loc) {
  std::string text;
  loc->walk([&](mlir::Location nested) {
    if (auto file = llvm::dyn_cast<mlir::FileLineColLoc>(nested)) {
      text = (file.getFilename().getValue() + ":" +
              llvm::Twine(file.getLine()) + ":" + llvm::Twine(file.getColumn()))
                 .str();
      return mlir::WalkResult::interrupt();
    }
    return mlir::WalkResult::advance();
  });
  if (text.empty()) {
    llvm::raw_string_ostream os(text);
    os << loc;
  }
  return text;
}

namespace {
/// Collects the MLIR diagnostics reported while it lives, so that they end
/// up in the llvm::Error of the step instead of on stderr.
class DiagnosticCollector {
public:
  explicit DiagnosticCollector(mlir::MLIRContext *context)
      : handler(context, [this](mlir::Diagnostic &diag) {
          llvm::raw_string_ostream os(text);
          os << describeLocation(diag.getLocation()) << ": "
             << (diag.getSeverity() == mlir::DiagnosticSeverity::Error
                     ? "error: "
                     : "note: ")
             << diag << "\n";
          for (mlir::Diagnostic &note : diag.getNotes())
            os << describeLocation(note.getLocation()) << ": note: " << note
               << "\n";
          return mlir::success();
        }) {}

  /// `what`, then the diagnostics.
  llvm::Error error(const llvm::Twine &what) const {
    return llvm::createStringError(
        what + "\n" +
        (text.empty() ? llvm::StringRef("(no diagnostic)")
                      : llvm::StringRef(text).rtrim()));
  }

private:
  std::string text;
  mlir::ScopedDiagnosticHandler handler;
};
} // namespace

GPUKernelTarget simit::gpuKernelTargetFor(int capability) {
  GPUKernelTarget target;
  target.chip = "sm_" + std::to_string(capability);
  // The PTX ISA version that introduced each newer chip (PTX ISA notes).
  int ptx = 80;
  if (capability == 103 || capability == 121)
    ptx = 88;
  else if (capability >= 120)
    ptx = 87;
  else if (capability >= 100)
    ptx = 86;
  target.features = "+ptx" + std::to_string(ptx);
  return target;
}

/// The simit-cpu-pipeline passes that work on the simit dialect before it
/// becomes loops, then simit-gpu-pipeline (which inlines and lowers the
/// rest itself).
static void buildGpuPipeline(mlir::OpPassManager &pm,
                             const mlir::simit::SimitCpuPipelineOptions &cpu,
                             const GPUKernelTarget &gpu) {
  mlir::simit::buildSimitScenePasses(pm, cpu);
  if (cpu.shermanMorrison)
    pm.addPass(mlir::simit::createSimitShermanMorrison());
  if (cpu.timePhases)
    pm.addPass(mlir::simit::createSimitTimePhases());
  if (cpu.checkNumerics)
    pm.addPass(mlir::simit::createSimitCheckNumerics());
  mlir::simit::SimitGpuPipelineOptions options;
  options.chip = gpu.chip;
  options.features = gpu.features;
  options.format = "isa";
  // The CPU path does not contract either: results agree to the rounding
  // of the summation order, not that of fused multiply-adds as well.
  options.fpContract = false;
  options.lowerSimit = true;
  pm.addPass(mlir::simit::createSimitGpuPipeline(options));
}

/// Precedes every kernel launch with `simit_rt_gpu_statement(where)`, where
/// is the source position of the set loop the kernel came from, so that the
/// runtime's errors name the Simit statement.
static void markLaunchStatements(mlir::ModuleOp module) {
  mlir::MLIRContext *context = module.getContext();
  auto ptr = mlir::LLVM::LLVMPointerType::get(context);
  llvm::SmallVector<mlir::gpu::LaunchFuncOp> launches;
  module.walk([&](mlir::gpu::LaunchFuncOp launch) { launches.push_back(launch); });
  if (launches.empty())
    return;
  mlir::OpBuilder builder(context);
  builder.setInsertionPointToEnd(module.getBody());
  auto marker = mlir::LLVM::LLVMFuncOp::create(
      builder, module.getLoc(),
      ::simit::abi::runtimeFunctionName(
          ::simit::abi::RuntimeFunction::GPUStatement),
      mlir::LLVM::LLVMFunctionType::get(mlir::LLVM::LLVMVoidType::get(context),
                                        {ptr}));
  for (auto [index, launch] : llvm::enumerate(launches)) {
    builder.setInsertionPoint(launch);
    mlir::Value text = mlir::LLVM::createGlobalString(
        launch.getLoc(), builder,
        "simit_gpu_statement_" + std::to_string(index),
        describeLocation(launch.getLoc()) + '\0',
        mlir::LLVM::Linkage::Internal);
    mlir::LLVM::CallOp::create(builder, launch.getLoc(), marker,
                               mlir::ValueRange{text});
  }
}

llvm::Error
simit::lowerToLLVM(mlir::ModuleOp module, LoweringResult &result,
                   mlir::simit::SimitCpuPipelineOptions pipelineOptions,
                   const std::optional<GPUKernelTarget> &gpu,
                   bool keepLoopsStage) {
  mlir::MLIRContext *context = module.getContext();
  DiagnosticCollector diagnostics(context);

  mlir::PassManager pm(context);
  // Verifying the whole module after each of the pipeline's ~40 passes took
  // as long as the passes themselves (neo-hookean.sim: 0.42 s of CPU for
  // the lowering, 0.24 s without). The module is verified once, at the
  // end, before it is translated; simit-opt, which the lit tests run, still
  // verifies after every pass.
  pm.enableVerifier(false);
  if (keepLoopsStage)
    pm.addInstrumentation(std::make_unique<LoopsStageKeeper>(result.loopsText));

  pipelineOptions.runtimeAllocator = true;
  if (gpu)
    buildGpuPipeline(pm, pipelineOptions, *gpu);
  else
    mlir::simit::buildSimitCpuPipeline(pm, pipelineOptions);

  if (mlir::failed(pm.run(module)))
    return diagnostics.error("lowering failed");
  if (mlir::failed(mlir::verify(module)))
    return diagnostics.error("lowering produced invalid IR");
  auto hasBindings = [](mlir::Operation *function) {
    return function &&
           function->hasAttr(llvm::StringRef(::simit::abi::kBindingsAttr));
  };
  for (auto function : module.getOps<mlir::LLVM::LLVMFuncOp>()) {
    if (!hasBindings(function))
      continue;
    // func-to-llvm copies the attributes onto the C interface wrapper
    // `_mlir_ciface_<name>` it makes; the engine calls the function itself.
    llvm::StringRef name = function.getSymName();
    if (name.consume_front("_mlir_ciface_") &&
        hasBindings(module.lookupSymbol(name)))
      continue;
    llvm::Expected<HostSignature> signature = readHostSignature(function);
    if (!signature)
      return signature.takeError();
    result.signatures[signature->function] = std::move(*signature);
  }
  if (gpu)
    markLaunchStatements(module);
  return llvm::Error::success();
}

/// Counts the LLVM arguments `signature` lowers to under `convention`.
static size_t loweredArgumentCount(const HostSignature &signature,
                                   MemRefConvention convention) {
  size_t count = 0;
  for (const ArgumentBinding &arg : signature.arguments)
    count += arg.type.isMemRef && convention == MemRefConvention::Descriptor
                 ? 3 + 2 * arg.type.rank()
                 : 1;
  return count;
}

/// The convention `function` declares in simit.memref_convention.
static llvm::Expected<MemRefConvention>
readMemRefConvention(mlir::LLVM::LLVMFuncOp function) {
  auto attr = function->getAttrOfType<mlir::StringAttr>(
      llvm::StringRef(::simit::abi::kMemRefConventionAttr));
  if (attr &&
      attr.getValue() == llvm::StringRef(::simit::abi::kDescriptorConvention))
    return MemRefConvention::Descriptor;
  if (attr &&
      attr.getValue() == llvm::StringRef(::simit::abi::kBarePointerConvention))
    return MemRefConvention::BarePointer;
  return llvm::createStringError(
      "function '" + function.getSymName() + "' declares no memref " +
      "convention in " + llvm::StringRef(::simit::abi::kMemRefConventionAttr) +
      " (simit-record-host-abi)");
}

/// Adds `void _mlir_<name>(void **args)` calling `function` with
/// `*args[i]` as argument i and storing its result, if any, at `*args[n]`:
/// the one signature through which the engine calls every function.
static void addPackedEntryPoint(llvm::Function &function) {
  llvm::LLVMContext &context = function.getContext();
  llvm::Type *ptr = llvm::PointerType::getUnqual(context);
  auto *entry = llvm::Function::Create(
      llvm::FunctionType::get(llvm::Type::getVoidTy(context), {ptr}, false),
      llvm::GlobalValue::ExternalLinkage, "_mlir_" + function.getName(),
      function.getParent());
  llvm::IRBuilder<> builder(llvm::BasicBlock::Create(context, "", entry));
  llvm::Value *args = entry->getArg(0);
  auto slot = [&](unsigned index) {
    return builder.CreateLoad(ptr,
                              builder.CreateConstGEP1_64(ptr, args, index));
  };
  llvm::SmallVector<llvm::Value *> values;
  for (llvm::Argument &param : function.args())
    values.push_back(
        builder.CreateLoad(param.getType(), slot(param.getArgNo())));
  llvm::CallInst *call = builder.CreateCall(&function, values);
  if (!call->getType()->isVoidTy())
    builder.CreateStore(call, slot(function.arg_size()));
  builder.CreateRetVoid();
}

/// Replaces the structor list `arrayName` (llvm.global_ctors or _dtors) by
/// `void name(void **)` that calls its functions in the order the platform
/// would: constructors by ascending priority, destructors by descending.
static void gatherStructors(llvm::Module &module, llvm::StringRef arrayName,
                            llvm::StringRef name) {
  llvm::LLVMContext &context = module.getContext();
  llvm::SmallVector<std::pair<uint64_t, llvm::Function *>> calls;
  if (llvm::GlobalVariable *list = module.getNamedGlobal(arrayName)) {
    if (auto *entries =
            llvm::dyn_cast<llvm::ConstantArray>(list->getInitializer()))
      for (llvm::Use &use : entries->operands()) {
        auto *entry = llvm::cast<llvm::ConstantStruct>(use.get());
        calls.push_back(
            {llvm::cast<llvm::ConstantInt>(entry->getOperand(0))->getZExtValue(),
             llvm::cast<llvm::Function>(entry->getOperand(1))});
      }
    list->eraseFromParent();
  }
  bool destructors = arrayName == "llvm.global_dtors";
  llvm::stable_sort(calls, [&](const auto &a, const auto &b) {
    return destructors ? a.first > b.first : a.first < b.first;
  });
  auto *function = llvm::Function::Create(
      llvm::FunctionType::get(llvm::Type::getVoidTy(context),
                              {llvm::PointerType::getUnqual(context)}, false),
      llvm::GlobalValue::ExternalLinkage, name, module);
  llvm::IRBuilder<> builder(llvm::BasicBlock::Create(context, "", function));
  for (const auto &call : calls)
    builder.CreateCall(call.second);
  builder.CreateRetVoid();
}

llvm::Expected<ObjectCode>
simit::compileToObject(mlir::ModuleOp llvmModule,
                       const llvm::StringMap<HostSignature> &signatures,
                       CompileTimes &times) {
  ObjectCode code;
  for (const auto &entry : signatures) {
    auto func = llvmModule.lookupSymbol<mlir::LLVM::LLVMFuncOp>(entry.getKey());
    if (!func)
      return llvm::createStringError("function '" + entry.getKey() +
                                     "' did not reach the LLVM dialect");
    CompiledFunction function;
    function.signature = entry.getValue();
    llvm::Expected<MemRefConvention> convention = readMemRefConvention(func);
    if (!convention)
      return convention.takeError();
    function.convention = *convention;
    // A conversion to LLVM that did not pass memrefs as declared would make
    // the engine pass the wrong words.
    size_t numArgs = func.getNumArguments();
    size_t expected = loweredArgumentCount(function.signature, *convention);
    if (numArgs != expected)
      return llvm::createStringError(
          "function '" + entry.getKey() + "' has " + llvm::Twine(numArgs) +
          " LLVM arguments where its host signature and memref convention "
          "make " +
          llvm::Twine(expected));
    code.functions[entry.getKey()] = std::move(function);
  }

  auto target = hostTarget();
  if (!target)
    return target.takeError();
  auto targetMachine = target->createTargetMachine();
  if (!targetMachine)
    return targetMachine.takeError();

  Stopwatch stopwatch;
  llvm::LLVMContext llvmContext;
  std::unique_ptr<llvm::Module> module;
  {
    DiagnosticCollector diagnostics(llvmModule.getContext());
    module = mlir::translateModuleToLLVMIR(llvmModule, llvmContext);
    if (!module)
      return diagnostics.error("translation to LLVM IR failed");
  }
  // The JIT runs no initializers (ObjectCode.cpp): the engine calls these.
  gatherStructors(*module, "llvm.global_ctors", "_simit_module_init");
  gatherStructors(*module, "llvm.global_dtors", "_simit_module_fini");
  mlir::ExecutionEngine::setupTargetTripleAndDataLayout(module.get(),
                                                        targetMachine->get());
  for (const auto &entry : code.functions)
    addPackedEntryPoint(*module->getFunction(entry.getKey()));
  code.dataLayout = module->getDataLayoutStr();
  times.optimizationMs = stopwatch.milliseconds();
  auto objects = compileToObjects(*module, *target, /*partitions=*/0, times);
  if (!objects)
    return objects.takeError();
  code.objects = std::move(*objects);
  return code;
}
