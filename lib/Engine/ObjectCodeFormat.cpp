//===--- ObjectCodeFormat.cpp - ObjectCode as bytes -----------------------===//
//
// Integers in the host's byte order (a cache entry is only ever read on the
// host it was compiled for), strings and lists with a 64-bit length first:
//
//   dataLayout, objects, functions, then per function: name, convention,
//   arguments (kind, set, field, rows, cols, name, mid, the edge sets of
//   union, gather and product bindings, index, chunk, type), results
//   (type); a type is scalar, isMemRef, isVector, isComplex, shape; then
//   extern sets, each a name and its fields (name, type), then extern
//   sets, each a name and its endpoint sets, then the extern tensors'
//   names.
//
//===----------------------------------------------------------------------===//

#include "ObjectCode.h"

#include <cstring>
#include <type_traits>

using namespace simit;

namespace {
class Writer {
public:
  template <typename T> void integer(T value) {
    static_assert(std::is_integral_v<T> || std::is_enum_v<T>);
    bytes.append(reinterpret_cast<const char *>(&value), sizeof(T));
  }
  void string(llvm::StringRef text) {
    integer<uint64_t>(text.size());
    bytes.append(text.data(), text.size());
  }
  void type(const ValueType &type) {
    integer(type.scalar);
    integer(type.isMemRef);
    integer(type.isVector);
    integer(type.isComplex);
    integer<uint64_t>(type.shape.size());
    for (int64_t dim : type.shape)
      integer(dim);
  }

  std::string bytes;
};

/// Reads what Writer wrote; the first read past the end, or an enum out of
/// range, sets `failed` and every later read yields zero.
class Reader {
public:
  explicit Reader(llvm::StringRef bytes) : rest(bytes) {}

  template <typename T> T integer() {
    T value{};
    if (failed || rest.size() < sizeof(T)) {
      failed = true;
      return value;
    }
    std::memcpy(&value, rest.data(), sizeof(T));
    rest = rest.drop_front(sizeof(T));
    return value;
  }
  /// An enum whose last enumerator is `last`.
  template <typename E> E enumeration(E last) {
    auto value = integer<std::underlying_type_t<E>>();
    if (value > static_cast<std::underlying_type_t<E>>(last))
      failed = true;
    return failed ? E{} : static_cast<E>(value);
  }
  bool boolean() {
    uint8_t value = integer<uint8_t>();
    if (value > 1)
      failed = true;
    return value == 1;
  }
  /// A count of items of at least `minBytes` each, which all must fit.
  uint64_t count(size_t minBytes) {
    uint64_t value = integer<uint64_t>();
    if (value > rest.size() / minBytes)
      failed = true;
    return failed ? 0 : value;
  }
  std::string string() {
    uint64_t size = count(1);
    std::string text = rest.take_front(size).str();
    rest = rest.drop_front(size);
    return text;
  }
  ValueType type() {
    ValueType type;
    type.scalar = enumeration(ScalarKind::String);
    type.isMemRef = boolean();
    type.isVector = boolean();
    type.isComplex = boolean();
    type.shape.resize(count(sizeof(int64_t)));
    for (int64_t &dim : type.shape)
      dim = integer<int64_t>();
    return type;
  }

  bool failed = false;
  llvm::StringRef rest;
};
} // namespace

std::string simit::serializeObjectCode(const ObjectCode &code) {
  Writer out;
  out.string(code.dataLayout);
  out.integer<uint64_t>(code.objects.size());
  for (const std::string &object : code.objects)
    out.string(object);
  out.integer<uint64_t>(code.functions.size());
  for (const auto &entry : code.functions) {
    const CompiledFunction &function = entry.getValue();
    out.string(entry.getKey());
    out.integer(function.convention);
    out.integer<uint64_t>(function.signature.arguments.size());
    for (const ArgumentBinding &arg : function.signature.arguments) {
      out.integer(arg.kind);
      for (const std::string *text : {&arg.set, &arg.field, &arg.rows,
                                       &arg.cols, &arg.name, &arg.offsets})
        out.string(*text);
      auto writeSets = [&](const std::vector<std::string> &sets) {
        out.integer<uint64_t>(sets.size());
        for (const std::string &set : sets)
          out.string(set);
      };
      writeSets(arg.edgeSets);
      writeSets(arg.partSets);
      out.integer<uint64_t>(arg.chains.size());
      for (const ArgumentBinding::ProductChain &chain : arg.chains) {
        writeSets(chain.mids);
        out.integer<uint64_t>(chain.factorSets.size());
        for (const std::vector<std::string> &sets : chain.factorSets)
          writeSets(sets);
      }
      out.integer(arg.partTransposed);
      out.integer(arg.index);
      out.integer(arg.chunk);
      out.integer(arg.declaredShape.has_value());
      if (arg.declaredShape) {
        out.integer<uint64_t>(arg.declaredShape->size());
        for (int64_t dim : *arg.declaredShape)
          out.integer(dim);
      }
      out.type(arg.type);
    }
    out.integer<uint64_t>(function.signature.results.size());
    for (const ValueType &result : function.signature.results)
      out.type(result);
  }
  out.integer<uint64_t>(code.externSetFields.size());
  for (const auto &[set, fields] : code.externSetFields) {
    out.string(set);
    out.integer<uint64_t>(fields.size());
    for (const DeclaredField &field : fields) {
      out.string(field.name);
      out.type(field.type);
    }
  }
  out.integer<uint64_t>(code.externSetEndpoints.size());
  for (const auto &[set, names] : code.externSetEndpoints) {
    out.string(set);
    out.integer<uint64_t>(names.size());
    for (const std::string &name : names)
      out.string(name);
  }
  out.integer<uint64_t>(code.externTensors.size());
  for (const std::string &name : code.externTensors)
    out.string(name);
  return std::move(out.bytes);
}

llvm::Expected<ObjectCode> simit::deserializeObjectCode(llvm::StringRef bytes) {
  Reader in(bytes);
  ObjectCode code;
  code.dataLayout = in.string();
  code.objects.resize(in.count(sizeof(uint64_t)));
  for (std::string &object : code.objects)
    object = in.string();
  // Every function and argument takes at least one length word.
  uint64_t numFunctions = in.count(sizeof(uint64_t));
  for (uint64_t i = 0; i < numFunctions && !in.failed; ++i) {
    std::string name = in.string();
    CompiledFunction function;
    function.signature.function = name;
    function.convention = in.enumeration(MemRefConvention::BarePointer);
    function.signature.arguments.resize(in.count(sizeof(uint64_t)));
    for (ArgumentBinding &arg : function.signature.arguments) {
      arg.kind = in.enumeration(ArgumentBinding::Kind::Parameter);
      for (std::string *text : {&arg.set, &arg.field, &arg.rows, &arg.cols,
                                 &arg.name, &arg.offsets})
        *text = in.string();
      auto readSets = [&](std::vector<std::string> &sets) {
        sets.resize(in.count(sizeof(uint64_t)));
        for (std::string &set : sets)
          set = in.string();
      };
      readSets(arg.edgeSets);
      readSets(arg.partSets);
      arg.chains.resize(in.count(sizeof(uint64_t)));
      for (ArgumentBinding::ProductChain &chain : arg.chains) {
        readSets(chain.mids);
        chain.factorSets.resize(in.count(sizeof(uint64_t)));
        for (std::vector<std::string> &sets : chain.factorSets)
          readSets(sets);
      }
      arg.partTransposed = in.integer<bool>();
      arg.index = in.integer<int64_t>();
      arg.chunk = in.integer<int64_t>();
      if (in.integer<bool>()) {
        arg.declaredShape.emplace(in.count(sizeof(int64_t)));
        for (int64_t &dim : *arg.declaredShape)
          dim = in.integer<int64_t>();
      }
      arg.type = in.type();
    }
    function.signature.results.resize(in.count(sizeof(uint64_t)));
    for (ValueType &result : function.signature.results)
      result = in.type();
    code.functions[name] = std::move(function);
  }
  uint64_t numSets = in.count(sizeof(uint64_t));
  for (uint64_t i = 0; i < numSets && !in.failed; ++i) {
    std::vector<DeclaredField> &fields = code.externSetFields[in.string()];
    fields.resize(in.count(sizeof(uint64_t)));
    for (DeclaredField &field : fields) {
      field.name = in.string();
      field.type = in.type();
    }
  }
  numSets = in.count(sizeof(uint64_t));
  for (uint64_t i = 0; i < numSets && !in.failed; ++i) {
    std::vector<std::string> &names = code.externSetEndpoints[in.string()];
    names.resize(in.count(sizeof(uint64_t)));
    for (std::string &name : names)
      name = in.string();
  }
  code.externTensors.resize(in.count(sizeof(uint64_t)));
  for (std::string &name : code.externTensors)
    name = in.string();
  if (in.failed || !in.rest.empty())
    return llvm::createStringError("malformed compiled code");
  return code;
}
