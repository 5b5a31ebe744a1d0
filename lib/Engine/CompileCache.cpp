//===--- CompileCache.cpp - Compiled programs kept on disk ----------------===//

#include "CompileCache.h"

#include "simit/Dialect/Simit/IR/Simit.h"
#include "simit/Dialect/Simit/Transforms/Passes.h"
#include "simit/Engine/Program.h"
#include "simit/Frontend/Frontend.h"
#include "simit/Frontend/IRGen.h"

#include "llvm/ADT/StringExtras.h"
#include "llvm/Config/llvm-config.h"
#include "llvm/Support/BLAKE3.h"
#include "llvm/Support/FileSystem.h"
#include "llvm/Support/MemoryBuffer.h"
#include "llvm/Support/Path.h"
#include "llvm/Support/Process.h"
#include "llvm/Support/raw_ostream.h"

#include <elf.h>
#include <link.h>

#include <cstring>

using namespace simit;

namespace {
constexpr llvm::StringLiteral kMagic = "SIMITOBJ";
/// Changes whenever the header or the payload's layout does (6: a list of
/// objects, one per partition of the module; 7: the declared shapes of
/// extern bindings; 8: the extern tensors' names).
constexpr uint32_t kFormatVersion = 8;
using Hash = llvm::BLAKE3Result<32>;

llvm::StringRef asText(const Hash &hash) {
  return {reinterpret_cast<const char *>(hash.data()), hash.size()};
}

Hash hashOf(llvm::StringRef bytes) {
  return llvm::BLAKE3::hash(llvm::arrayRefFromStringRef(bytes));
}

/// The GNU build ID note of the loaded ELF object that holds `address`.
std::string buildIdContaining(const void *address) {
  struct Search {
    uintptr_t address;
    std::string buildId;
  } search{reinterpret_cast<uintptr_t>(address), ""};
  dl_iterate_phdr(
      [](dl_phdr_info *info, size_t, void *data) {
        auto &search = *static_cast<Search *>(data);
        auto segments = llvm::ArrayRef(info->dlpi_phdr, info->dlpi_phnum);
        bool holds = llvm::any_of(segments, [&](const ElfW(Phdr) & segment) {
          uintptr_t start = info->dlpi_addr + segment.p_vaddr;
          return segment.p_type == PT_LOAD && search.address >= start &&
                 search.address < start + segment.p_memsz;
        });
        if (!holds)
          return 0;
        for (const ElfW(Phdr) & segment : segments) {
          if (segment.p_type != PT_NOTE)
            continue;
          const char *note =
              reinterpret_cast<const char *>(info->dlpi_addr + segment.p_vaddr);
          const char *end = note + segment.p_memsz;
          while (note + sizeof(ElfW(Nhdr)) <= end) {
            auto *header = reinterpret_cast<const ElfW(Nhdr) *>(note);
            const char *name = note + sizeof(ElfW(Nhdr));
            const char *desc = name + llvm::alignTo(header->n_namesz, 4);
            if (header->n_type == NT_GNU_BUILD_ID && header->n_namesz == 4 &&
                std::memcmp(name, "GNU", 4) == 0)
              search.buildId = llvm::toHex(
                  llvm::StringRef(desc, header->n_descsz), /*LowerCase=*/true);
            note = desc + llvm::alignTo(header->n_descsz, 4);
          }
        }
        return 1;
      },
      &search);
  return search.buildId;
}
} // namespace

const std::string &simit::compilerIdentity() {
  static const std::string identity = [] {
    // A function of each library whose code decides what is compiled: they
    // are shared libraries in a default build, one binary when linked
    // statically.
    const void *anchors[] = {
        reinterpret_cast<const void *>(&compilerIdentity),
        reinterpret_cast<const void *>(&frontend::parseProgram),
        reinterpret_cast<const void *>(&frontend::generateIR),
        reinterpret_cast<const void *>(&mlir::simit::isScalarType),
        reinterpret_cast<const void *>(&mlir::simit::buildSimitCpuPipeline)};
    llvm::SmallVector<std::string> buildIds;
    for (const void *anchor : anchors) {
      std::string buildId = buildIdContaining(anchor);
      if (buildId.empty())
        return std::string();
      if (!llvm::is_contained(buildIds, buildId))
        buildIds.push_back(buildId);
    }
    return "simit " SIMIT_VERSION " llvm " LLVM_VERSION_STRING " builds " +
           llvm::join(buildIds, ",");
  }();
  return identity;
}

std::string simit::defaultCompileCacheDirectory() {
  llvm::SmallString<128> path;
  if (std::optional<std::string> xdg =
          llvm::sys::Process::GetEnv("XDG_CACHE_HOME");
      xdg && !xdg->empty())
    path = *xdg;
  else if (std::optional<std::string> home = llvm::sys::Process::GetEnv("HOME");
           home && !home->empty())
    llvm::sys::path::append(path, *home, ".cache");
  else
    return "";
  llvm::sys::path::append(path, "simit");
  return std::string(path);
}

std::string simit::cacheEntryPath(llvm::StringRef directory,
                                  llvm::StringRef key) {
  llvm::SmallString<128> path(directory);
  llvm::sys::path::append(
      path, llvm::toHex(asText(hashOf(key)).take_front(16), true) + ".o.simit");
  return std::string(path);
}

std::optional<std::string> simit::readCacheEntry(llvm::StringRef directory,
                                                 llvm::StringRef key) {
  auto file = llvm::MemoryBuffer::getFile(cacheEntryPath(directory, key),
                                          /*IsText=*/false,
                                          /*RequiresNullTerminator=*/false);
  if (!file)
    return std::nullopt;
  llvm::StringRef rest = (*file)->getBuffer();
  auto take = [&](size_t size) {
    llvm::StringRef taken = rest.take_front(size);
    rest = rest.drop_front(size);
    return taken;
  };
  auto takeInteger = [&](auto value) {
    llvm::StringRef bytes = take(sizeof(value));
    if (bytes.size() == sizeof(value))
      std::memcpy(&value, bytes.data(), sizeof(value));
    return value;
  };
  if (take(kMagic.size()) != kMagic ||
      takeInteger(uint32_t(0)) != kFormatVersion)
    return std::nullopt;
  uint64_t keySize = takeInteger(uint64_t(0));
  if (keySize != key.size() || take(keySize) != key)
    return std::nullopt;
  uint64_t payloadSize = takeInteger(uint64_t(0));
  llvm::StringRef hash = take(sizeof(Hash));
  if (rest.size() != payloadSize || hash != asText(hashOf(rest)))
    return std::nullopt;
  return rest.str();
}

llvm::Error simit::writeCacheEntry(llvm::StringRef directory,
                                   llvm::StringRef key,
                                   llvm::StringRef payload) {
  if (std::error_code ec = llvm::sys::fs::create_directories(directory))
    return llvm::createStringError(ec, directory + ": " + ec.message());
  std::string path = cacheEntryPath(directory, key);
  int fd;
  llvm::SmallString<128> temporary;
  if (std::error_code ec = llvm::sys::fs::createUniqueFile(
          path + ".tmp-%%%%%%%%", fd, temporary))
    return llvm::createStringError(ec, path + ": " + ec.message());
  {
    llvm::raw_fd_ostream os(fd, /*shouldClose=*/true);
    auto writeInteger = [&](auto value) {
      os.write(reinterpret_cast<const char *>(&value), sizeof(value));
    };
    os << kMagic;
    writeInteger(kFormatVersion);
    writeInteger(uint64_t(key.size()));
    os << key;
    writeInteger(uint64_t(payload.size()));
    os << asText(hashOf(payload)) << payload;
    os.close();
    if (os.has_error()) {
      std::error_code ec = os.error();
      os.clear_error();
      llvm::sys::fs::remove(temporary);
      return llvm::createStringError(ec, temporary + ": " + ec.message());
    }
  }
  if (std::error_code ec = llvm::sys::fs::rename(temporary, path)) {
    llvm::sys::fs::remove(temporary);
    return llvm::createStringError(ec, path + ": " + ec.message());
  }
  return llvm::Error::success();
}
