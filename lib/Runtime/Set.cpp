//===--- Set.cpp - Hypergraph sets with fields stored as arrays -----------===//

#include "simit/Runtime/Set.h"

#include "simit/Runtime/SparsityPattern.h"

#include "MemoryBudget.h"

#include "llvm/Support/ErrorHandling.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>

using namespace simit;

static constexpr size_t kFieldAlignment = 64;

size_t simit::componentSize(ComponentType type) {
  switch (type) {
  case ComponentType::Float64:
    return 8;
  case ComponentType::Float32:
  case ComponentType::Int32:
    return 4;
  case ComponentType::Bool:
    return 1;
  }
  llvm_unreachable("unknown component type");
}

llvm::StringRef simit::componentTypeName(ComponentType type) {
  switch (type) {
  case ComponentType::Float64:
    return "float64";
  case ComponentType::Float32:
    return "float32";
  case ComponentType::Int32:
    return "int32";
  case ComponentType::Bool:
    return "bool";
  }
  llvm_unreachable("unknown component type");
}

size_t FieldDescriptor::blockSize() const {
  size_t size = 1;
  for (int dim : shape)
    size *= static_cast<size_t>(dim);
  return size;
}

Set::Set(llvm::StringRef name) : setName(name.str()) {}

Set::Set(llvm::StringRef name, llvm::ArrayRef<Set *> endpointList)
    : setName(name.str()), endpointSets(endpointList.begin(),
                                        endpointList.end()) {
  for (Set *endpointSet : endpointSets)
    if (std::find(endpointSet->dependents.begin(),
                  endpointSet->dependents.end(),
                  this) == endpointSet->dependents.end())
      endpointSet->dependents.push_back(this);
}

Set::~Set() {
  for (Set *endpointSet : endpointSets) {
    if (!endpointSet)
      continue; // destroyed first
    auto &list = endpointSet->dependents;
    list.erase(std::remove(list.begin(), list.end(), this), list.end());
  }
  // Edge sets over this one must not outlive it; forget them so that their
  // destructors do not touch this set.
  for (Set *dependent : dependents)
    for (Set *&endpointSet : dependent->endpointSets)
      if (endpointSet == this)
        endpointSet = nullptr;
}

llvm::Expected<std::unique_ptr<Set>>
Set::makeGrid(Set &points, llvm::ArrayRef<int> dims, llvm::StringRef name) {
  if (dims.empty())
    return llvm::createStringError("grid '" + name +
                                   "': expected at least one dimension");
  if (points.isEdgeSet())
    return llvm::createStringError("grid '" + name + "': the point set '" +
                                   points.name() + "' is an edge set");
  long long count = 1;
  for (int dim : dims) {
    if (dim <= 0)
      return llvm::createStringError("grid '" + name +
                                     "': expected positive dimensions, "
                                     "found " +
                                     llvm::Twine(dim));
    count *= dim;
    if (count > INT32_MAX / static_cast<long long>(dims.size()))
      return llvm::createStringError("grid '" + name + "': too many points");
  }
  if (points.size() != 0 && points.size() != count)
    return llvm::createStringError(
        "grid '" + name + "': the point set '" + points.name() + "' has " +
        llvm::Twine(points.size()) + " points, expected " +
        llvm::Twine(count));
  if (points.size() == 0) {
    points.reserve(static_cast<int>(count));
    for (long long i = 0; i < count; ++i)
      points.add();
  }
  Set *endpointPair[2] = {&points, &points};
  auto grid = std::make_unique<Set>(name, endpointPair);
  grid->gridDims.assign(dims.begin(), dims.end());
  int d = static_cast<int>(dims.size());
  grid->reserve(static_cast<int>(count) * d);
  // Strides of the row-major point numbering.
  std::vector<long long> stride(d, 1);
  for (int a = d - 2; a >= 0; --a)
    stride[a] = stride[a + 1] * dims[a + 1];
  for (long long p = 0; p < count; ++p)
    for (int a = 0; a < d; ++a) {
      long long coordinate = (p / stride[a]) % dims[a];
      long long next = coordinate + 1 == dims[a]
                           ? p - coordinate * stride[a]
                           : p + stride[a];
      grid->add(static_cast<int>(p), static_cast<int>(next));
    }
  return grid;
}

void Set::fatal(const llvm::Twine &message) const {
  llvm::report_fatal_error("simit::Set '" + llvm::Twine(setName) + "': " +
                           message);
}

//===--- Elements ---------------------------------------------------------===//

void Set::reserve(int n) {
  if (n <= capacity)
    return;
  for (FieldStorage &storage : fieldStorage) {
    FieldStorage bigger = makeStorage(storage.descriptor, n);
    std::memcpy(bigger.data.get(), storage.data.get(),
                numElements * storage.descriptor.blockBytes());
    storage.data = std::move(bigger.data);
  }
  endpoints.reserve(static_cast<size_t>(n) * cardinality());
  capacity = n;
  ++setVersion;
}

void Set::grow(int needed) {
  if (needed > capacity)
    reserve(std::max({needed, 2 * capacity, 16}));
}

int Set::add() {
  if (isEdgeSet())
    fatal("add() without endpoints on an edge set of cardinality " +
          llvm::Twine(cardinality()));
  grow(numElements + 1);
  zeroElement(numElements);
  ++setVersion;
  return numElements++;
}

llvm::Error Set::checkEndpoints(llvm::ArrayRef<int> list) const {
  if (list.size() != endpointSets.size())
    return llvm::createStringError(
        "set '" + setName + "': expected " + llvm::Twine(cardinality()) +
        " endpoints, found " + llvm::Twine(list.size()));
  for (size_t i = 0; i < list.size(); ++i) {
    int size = endpointSets[i] ? endpointSets[i]->size() : 0;
    if (list[i] < 0 || list[i] >= size)
      return llvm::createStringError(
          "set '" + setName + "': endpoint " + llvm::Twine(i) + " is " +
          llvm::Twine(list[i]) + ", out of range for set '" +
          (endpointSets[i] ? endpointSets[i]->name() : "<destroyed>") +
          "' of size " + llvm::Twine(size));
  }
  return llvm::Error::success();
}

int Set::add(llvm::ArrayRef<int> list) {
  if (llvm::Error err = checkEndpoints(list))
    fatal(llvm::toString(std::move(err)));
  grow(numElements + 1);
  zeroElement(numElements);
  endpoints.insert(endpoints.end(), list.begin(), list.end());
  ++setVersion;
  return numElements++;
}

void Set::zeroElement(int e) {
  // A slot freed by remove() still holds the old element's data.
  for (FieldStorage &storage : fieldStorage) {
    size_t bytes = storage.descriptor.blockBytes();
    std::memset(storage.data.get() + e * bytes, 0, bytes);
  }
}

void Set::moveElement(int from, int to) {
  for (FieldStorage &storage : fieldStorage) {
    size_t bytes = storage.descriptor.blockBytes();
    std::memcpy(storage.data.get() + to * bytes,
                storage.data.get() + from * bytes, bytes);
  }
  int c = cardinality();
  std::copy_n(endpoints.begin() + static_cast<size_t>(from) * c, c,
              endpoints.begin() + static_cast<size_t>(to) * c);
}

void Set::remove(int e) {
  if (e < 0 || e >= numElements)
    fatal("remove(" + llvm::Twine(e) + ") out of range for size " +
          llvm::Twine(numElements));
  int last = numElements - 1;
  if (e != last)
    moveElement(last, e);
  endpoints.resize(static_cast<size_t>(last) * cardinality());
  numElements = last;
  ++setVersion;
  for (Set *dependent : std::vector<Set *>(dependents))
    dependent->endpointRemoved(*this, e, last);
}

void Set::endpointRemoved(const Set &endpointSet, int removed, int moved) {
  int c = cardinality();
  // Walk backwards so that an edge moved into a freed slot was already seen.
  for (int edge = numElements - 1; edge >= 0; --edge) {
    for (int i = 0; i < c; ++i) {
      if (endpointSets[i] != &endpointSet ||
          endpoints[static_cast<size_t>(edge) * c + i] != removed)
        continue;
      remove(edge);
      break;
    }
  }
  if (moved == removed)
    return;
  for (int edge = 0; edge < numElements; ++edge)
    for (int i = 0; i < c; ++i)
      if (endpointSets[i] == &endpointSet &&
          endpoints[static_cast<size_t>(edge) * c + i] == moved)
        endpoints[static_cast<size_t>(edge) * c + i] = removed;
}

//===--- Fields -----------------------------------------------------------===//

Set::FieldStorage Set::makeStorage(FieldDescriptor descriptor,
                                   int elements) const {
  size_t bytes = std::max<size_t>(1, elements) * descriptor.blockBytes();
  bytes = (bytes + kFieldAlignment - 1) / kFieldAlignment * kFieldAlignment;
  auto *memory = static_cast<std::byte *>(std::aligned_alloc(kFieldAlignment,
                                                             bytes));
  if (!memory)
    fatal("out of memory for field '" + descriptor.name + "'");
  std::memset(memory, 0, bytes);
  return FieldStorage{std::move(descriptor),
                      {memory, [](std::byte *p) { std::free(p); }}};
}

int Set::findField(llvm::StringRef name) const {
  for (size_t i = 0; i < fieldStorage.size(); ++i)
    if (fieldStorage[i].descriptor.name == name)
      return static_cast<int>(i);
  return -1;
}

llvm::Error Set::addField(llvm::StringRef name, ComponentType type,
                          llvm::ArrayRef<int> shape) {
  if (name.empty())
    return llvm::createStringError("set '" + setName +
                                   "': a field needs a name");
  if (hasField(name))
    return llvm::createStringError("set '" + setName + "': field '" + name +
                                   "' already exists");
  for (int dim : shape)
    if (dim <= 0)
      return llvm::createStringError(
          "set '" + setName + "': field '" + name +
          "': expected positive dimensions, found " + llvm::Twine(dim));
  std::vector<uint64_t> factors(shape.begin(), shape.end());
  factors.push_back(componentSize(type));
  factors.push_back(std::max(1, capacity));
  if (llvm::Error err = detail::checkMemoryRequest(
          detail::checkedProduct(factors),
          "field '" + name + "' of set '" + setName + "'"))
    return err;
  FieldDescriptor descriptor{name.str(), type, {shape.begin(), shape.end()}};
  fieldStorage.push_back(makeStorage(std::move(descriptor), capacity));
  ++setVersion;
  return llvm::Error::success();
}

void Set::removeField(llvm::StringRef name) {
  int index = findField(name);
  if (index < 0)
    fatal("no field '" + name + "' to remove");
  fieldStorage.erase(fieldStorage.begin() + index);
  ++setVersion;
}

const FieldDescriptor *Set::fieldDescriptor(llvm::StringRef name) const {
  int index = findField(name);
  return index < 0 ? nullptr : &fieldStorage[index].descriptor;
}

std::vector<const FieldDescriptor *> Set::fields() const {
  std::vector<const FieldDescriptor *> list;
  for (const FieldStorage &storage : fieldStorage)
    list.push_back(&storage.descriptor);
  return list;
}

void *Set::fieldData(llvm::StringRef name) {
  int index = findField(name);
  return index < 0 ? nullptr : fieldStorage[index].data.get();
}

const void *Set::fieldData(llvm::StringRef name) const {
  int index = findField(name);
  return index < 0 ? nullptr : fieldStorage[index].data.get();
}
