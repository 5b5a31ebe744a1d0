//===--- AtomicFile.cpp - Output files that appear only when complete -----===//

#include "AtomicFile.h"

using namespace simit;
using namespace simit::detail;

AtomicFile::AtomicFile(std::string path,
                       std::optional<llvm::sys::fs::TempFile> temp)
    : path(std::move(path)), temp(std::move(temp)) {
  if (this->temp) {
    ownedStream = std::make_unique<llvm::raw_fd_ostream>(this->temp->FD,
                                                         /*shouldClose=*/false);
    os = ownedStream.get();
  } else {
    os = &llvm::outs();
  }
}

llvm::Expected<std::unique_ptr<AtomicFile>>
AtomicFile::create(llvm::StringRef path) {
  if (path == "-")
    return std::unique_ptr<AtomicFile>(new AtomicFile("-", std::nullopt));
  auto temp = llvm::sys::fs::TempFile::create(path + ".tmp-%%%%%%");
  if (!temp)
    return llvm::createStringError(path + ": cannot write: " +
                                   llvm::toString(temp.takeError()));
  return std::unique_ptr<AtomicFile>(new AtomicFile(path.str(),
                                                    std::move(*temp)));
}

AtomicFile::~AtomicFile() {
  if (!temp)
    return;
  // Uncommitted: whatever went wrong was reported; drop the partial file.
  if (ownedStream) {
    ownedStream->clear_error();
    ownedStream.reset();
  }
  llvm::consumeError(temp->discard());
}

llvm::Error AtomicFile::failure(const llvm::Twine &reason) const {
  return llvm::createStringError(path + ": cannot write: " + reason);
}

llvm::Error AtomicFile::flush() {
  os->flush();
  if (!ownedStream || !ownedStream->has_error())
    return llvm::Error::success();
  std::string reason = ownedStream->error().message();
  ownedStream->clear_error();
  return failure(reason);
}

llvm::Error AtomicFile::commit() {
  if (llvm::Error err = flush())
    return err;
  if (!temp)
    return llvm::Error::success();
  ownedStream.reset();
  llvm::Error kept = temp->keep(path);
  temp.reset();
  if (kept)
    return failure(llvm::toString(std::move(kept)));
  return llvm::Error::success();
}

llvm::Error detail::writeFileAtomically(
    llvm::StringRef path,
    llvm::function_ref<llvm::Error(llvm::raw_ostream &)> write) {
  auto file = AtomicFile::create(path);
  if (!file)
    return file.takeError();
  if (llvm::Error err = write((*file)->stream()))
    return err;
  return (*file)->commit();
}
