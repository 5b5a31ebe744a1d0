//===- Frontend.cpp - Simit frontend entry points -------------------------===//

#include "simit/Frontend/Frontend.h"
#include "simit/Frontend/Parser.h"
#include "simit/Frontend/Sema.h"

using namespace simit::frontend;

std::unique_ptr<Program>
simit::frontend::parseProgram(llvm::SourceMgr &sourceMgr, unsigned bufferId,
                              DiagnosticEngine &diags) {
  return parse(sourceMgr.getMemoryBuffer(bufferId)->getBuffer(), diags);
}

bool simit::frontend::checkProgram(Program &program, DiagnosticEngine &diags) {
  return check(program, diags);
}

std::vector<Section> simit::frontend::splitSections(llvm::StringRef source) {
  std::vector<Section> sections;
  if (!source.starts_with("%%%")) {
    Section whole;
    whole.text = source;
    sections.push_back(whole);
    return sections;
  }
  // Offsets of every line that starts with `%%%`.
  std::vector<size_t> starts;
  std::vector<unsigned> lines;
  unsigned line = 1;
  for (size_t pos = 0; pos < source.size();) {
    if (source.substr(pos).starts_with("%%%")) {
      starts.push_back(pos);
      lines.push_back(line);
    }
    size_t eol = source.find('\n', pos);
    if (eol == llvm::StringRef::npos)
      break;
    pos = eol + 1;
    ++line;
  }
  for (size_t i = 0; i < starts.size(); ++i) {
    size_t end = i + 1 < starts.size() ? starts[i + 1] : source.size();
    Section section;
    section.text = source.slice(starts[i], end);
    section.index = i;
    section.firstLine = lines[i];
    llvm::StringRef header = section.text.substr(3);
    header = header.take_until([](char c) { return c == '\n' || c == '\r'; });
    section.disabled = header.starts_with("-");
    section.name = (section.disabled ? header.drop_front() : header).trim().str();
    sections.push_back(section);
  }
  return sections;
}
