//===--- BCSRArrays.h - BCSR matrices of lowered code ---------------------===//
//
// Lowered code passes a system matrix with square blocks as BCSR arrays:
// rowptr memref<?xi32>, colidx memref<?xi32>, values memref<?xBxBxT>.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_LIB_ABI_BCSRARRAYS_H
#define SIMIT_LIB_ABI_BCSRARRAYS_H

#include "RunState.h"

#include "simit/ABI/MemRef.h"
#include "simit/Runtime/Solvers.h"

#include <cstdint>

namespace simit {
namespace abi {

/// The view of BCSR arrays with square blocks (values memref<?xBxBxT>).
template <typename T>
bool bcsrView(MemRefDescriptor<int32_t, 1> *rowptr,
              MemRefDescriptor<int32_t, 1> *colidx,
              MemRefDescriptor<T, 3> *values, const char *where,
              simit::SquareBCSRView<T> &view) {
  if (!isContiguous(*rowptr) || !isContiguous(*colidx) ||
      !isContiguous(*values) || values->sizes[1] != values->sizes[2] ||
      rowptr->sizes[0] < 1)
    return fail(where, "malformed BCSR arrays of a square matrix");
  view.rows = rowptr->sizes[0] - 1;
  view.blockSize = values->sizes[1];
  view.rowptr = rowptr->data + rowptr->offset;
  view.colidx = colidx->data + colidx->offset;
  view.values = values->data + values->offset;
  return true;
}

} // namespace abi
} // namespace simit

#endif // SIMIT_LIB_ABI_BCSRARRAYS_H
