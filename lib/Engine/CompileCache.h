//===--- CompileCache.h - Compiled programs kept on disk ------------------===//
//
// One file per key: a header (magic, format version, the whole key, the
// payload's size and BLAKE3 hash) and the payload. The file is named by the
// hash of the key, written to a temporary file and renamed, so a reader
// sees a whole entry or none; an entry whose header, key, size or hash does
// not match is treated as absent, so it is compiled again and overwritten.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_LIB_ENGINE_COMPILECACHE_H
#define SIMIT_LIB_ENGINE_COMPILECACHE_H

#include "llvm/ADT/StringRef.h"
#include "llvm/Support/Error.h"

#include <optional>
#include <string>

namespace simit {

/// The compiler as the cache key names it: the project's and LLVM's
/// versions and the GNU build IDs of the binaries that hold the frontend,
/// the dialect, its passes and the engine, so a rebuilt compiler never
/// reads its predecessor's code. Empty when one has no build ID (the cache
/// is not used then).
const std::string &compilerIdentity();

/// The file `key`'s entry lives in under `directory`.
std::string cacheEntryPath(llvm::StringRef directory, llvm::StringRef key);

/// The payload of `key`'s entry, if there is a whole, uncorrupted one.
std::optional<std::string> readCacheEntry(llvm::StringRef directory,
                                          llvm::StringRef key);

/// Stores `payload` as `key`'s entry, creating `directory` if needed.
llvm::Error writeCacheEntry(llvm::StringRef directory, llvm::StringRef key,
                            llvm::StringRef payload);

} // namespace simit

#endif // SIMIT_LIB_ENGINE_COMPILECACHE_H
