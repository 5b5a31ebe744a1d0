//===--- PerfMap.cpp - Naming JIT-compiled code for perf -------------------===//

#include "PerfMap.h"

#include "llvm/ExecutionEngine/JITLink/JITLink.h"
#include "llvm/ExecutionEngine/Orc/ObjectLinkingLayer.h"
#include "llvm/Support/Format.h"
#include "llvm/Support/Path.h"
#include "llvm/Support/Process.h"
#include "llvm/Support/raw_ostream.h"

#include <mutex>
#include <unistd.h>

using namespace simit;

namespace {
/// Appends the address, size and name of every function of a linked graph
/// to the process's perf map once its addresses are final.
class PerfMapPlugin : public llvm::orc::ObjectLinkingLayer::Plugin {
public:
  explicit PerfMapPlugin(std::string path) : path(std::move(path)) {}

  void modifyPassConfig(llvm::orc::MaterializationResponsibility &,
                        llvm::jitlink::LinkGraph &,
                        llvm::jitlink::PassConfiguration &config) override {
    // Local functions (the outlined OpenMP bodies) would lose their
    // symbols to pruning, their code staying: keep the names.
    config.PrePrunePasses.push_back([](llvm::jitlink::LinkGraph &graph) {
      for (llvm::jitlink::Symbol *symbol : graph.defined_symbols())
        if (symbol->hasName() && symbol->isCallable())
          symbol->setLive(true);
      return llvm::Error::success();
    });
    config.PostFixupPasses.push_back([this](llvm::jitlink::LinkGraph &graph) {
      static std::mutex fileMutex;
      std::lock_guard<std::mutex> lock(fileMutex);
      std::error_code error;
      llvm::raw_fd_ostream map(path, error,
                               llvm::sys::fs::OF_Append |
                                   llvm::sys::fs::OF_Text);
      // A map that cannot be written costs the profile its names, not the
      // run its code.
      if (error)
        return llvm::Error::success();
      for (llvm::jitlink::Symbol *symbol : graph.defined_symbols())
        if (symbol->hasName() && symbol->isCallable() && symbol->getSize())
          map << llvm::format_hex_no_prefix(symbol->getAddress().getValue(), 1)
              << ' ' << llvm::format_hex_no_prefix(symbol->getSize(), 1)
              << ' ' << *symbol->getName() << '\n';
      return llvm::Error::success();
    });
  }
  llvm::Error notifyFailed(llvm::orc::MaterializationResponsibility &) override {
    return llvm::Error::success();
  }
  llvm::Error notifyRemovingResources(llvm::orc::JITDylib &,
                                      llvm::orc::ResourceKey) override {
    return llvm::Error::success();
  }
  void notifyTransferringResources(llvm::orc::JITDylib &,
                                   llvm::orc::ResourceKey,
                                   llvm::orc::ResourceKey) override {}

private:
  std::string path;
};
} // namespace

void simit::addPerfMapWhenAsked(llvm::orc::LLJIT &jit) {
  std::optional<std::string> directory =
      llvm::sys::Process::GetEnv("SIMIT_PERF_MAP");
  if (!directory || directory->empty())
    return;
  llvm::SmallString<128> path(*directory);
  llvm::sys::path::append(path,
                          "perf-" + std::to_string(::getpid()) + ".map");
  if (auto *layer =
          llvm::dyn_cast<llvm::orc::ObjectLinkingLayer>(&jit.getObjLinkingLayer()))
    layer->addPlugin(std::make_shared<PerfMapPlugin>(std::string(path)));
}
