//===--- CSV.cpp - Comma separated output of set fields -------------------===//

#include "simit/Runtime/CSV.h"

#include "AtomicFile.h"
#include "FieldText.h"

using namespace simit;

llvm::Error simit::checkCSVFields(const Set &set,
                                  llvm::ArrayRef<std::string> fields) {
  for (const std::string &field : fields)
    if (!set.fieldDescriptor(field))
      return llvm::createStringError("CSV output of set '" + set.name() +
                                     "': no field '" + field + "'");
  return llvm::Error::success();
}

std::string simit::csvHeader(const Set &set,
                             llvm::ArrayRef<std::string> fields,
                             bool withFrame) {
  std::string header = withFrame ? "frame,element" : "element";
  for (const std::string &name : fields) {
    const FieldDescriptor *field = set.fieldDescriptor(name);
    if (!field)
      continue;
    size_t blockSize = field->blockSize();
    for (size_t i = 0; i < blockSize; ++i) {
      header += "," + name;
      // Row-major multi-index of component i.
      std::string suffix;
      size_t rest = i;
      for (size_t d = field->shape.size(); d-- > 0;) {
        suffix = "_" + std::to_string(rest % field->shape[d]) + suffix;
        rest /= field->shape[d];
      }
      header += suffix;
    }
  }
  return header + "\n";
}

llvm::Error simit::writeCSVRows(llvm::raw_ostream &os, const Set &set,
                                llvm::ArrayRef<std::string> fields,
                                std::optional<int> frame) {
  if (llvm::Error err = checkCSVFields(set, fields))
    return err;
  std::vector<std::pair<const FieldDescriptor *, const void *>> columns;
  for (const std::string &name : fields)
    columns.push_back({set.fieldDescriptor(name), set.fieldData(name)});
  for (int e = 0; e < set.size(); ++e) {
    if (frame)
      os << *frame << ',';
    os << e;
    for (auto [field, data] : columns) {
      size_t blockSize = field->blockSize();
      for (size_t i = 0; i < blockSize; ++i) {
        os << ',';
        detail::writeComponent(os, data, field->type, e * blockSize + i);
      }
    }
    os << '\n';
  }
  return llvm::Error::success();
}

llvm::Error simit::writeCSV(llvm::StringRef path, const Set &set,
                            llvm::ArrayRef<std::string> fields) {
  if (llvm::Error err = checkCSVFields(set, fields))
    return err;
  return detail::writeFileAtomically(path, [&](llvm::raw_ostream &os) {
    os << csvHeader(set, fields, false);
    return writeCSVRows(os, set, fields, std::nullopt);
  });
}
