//===--- CSV.h - Comma separated output of set fields -----------*- C++ -*-===//
//
// One row per element: an optional frame column, the element index, then
// every component of the chosen fields. Columns of a scalar field are named
// after it, those of a tensor field `name_i` / `name_i_j` (row-major).
// Numbers are written with 17 significant digits, so they read back exactly.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_RUNTIME_CSV_H
#define SIMIT_RUNTIME_CSV_H

#include "simit/Runtime/Set.h"

#include "llvm/ADT/ArrayRef.h"
#include "llvm/Support/Error.h"
#include "llvm/Support/raw_ostream.h"

#include <optional>
#include <string>

namespace simit {

/// An error unless every field exists on `set`.
llvm::Error checkCSVFields(const Set &set, llvm::ArrayRef<std::string> fields);

/// The header line (with its newline).
std::string csvHeader(const Set &set, llvm::ArrayRef<std::string> fields,
                      bool withFrame);

/// One row per element, with `frame` as the first column when given.
llvm::Error writeCSVRows(llvm::raw_ostream &os, const Set &set,
                         llvm::ArrayRef<std::string> fields,
                         std::optional<int> frame);

/// A whole file: the header, then the rows. The file is written under a
/// temporary name and renamed to `path` when complete.
llvm::Error writeCSV(llvm::StringRef path, const Set &set,
                     llvm::ArrayRef<std::string> fields);

} // namespace simit

#endif // SIMIT_RUNTIME_CSV_H
