//===--- ConformanceProgram.h - Simit text of conformance cases -*- C++ -*-===//
//
// Writes the Simit program of a case: the element types and extern sets of
// the scene, an assembly function per (source, fields) of its operands, and
// the exported function Case::name() that assembles the operands, applies
// the operation and writes what the case observes (ConformanceCases.h).
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_UNITTESTS_ENGINE_CONFORMANCEPROGRAM_H
#define SIMIT_UNITTESTS_ENGINE_CONFORMANCEPROGRAM_H

#include "ConformanceCases.h"

#include <string>

namespace simit::conformance {

std::string generateProgram(const Case &c);

} // namespace simit::conformance

#endif // SIMIT_UNITTESTS_ENGINE_CONFORMANCEPROGRAM_H
