//===--- LaneSums.h - Sums of the runtime's passes in running lanes -------===//
//
// A sum over a pass kept in several running sums that take the indices in
// turn and are added in a fixed order at the end. With one running sum
// every addition waits for the one before (about 4 cycles), which bounded
// the solvers' passes rather than memory; the order is still fixed, so the
// results do not depend on threads or timing.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_LIB_RUNTIME_LANESUMS_H
#define SIMIT_LIB_RUNTIME_LANESUMS_H

#include <cstdint>

namespace simit {

template <int64_t Lanes> struct LaneSums {
  double lane[Lanes] = {};
  double total() const {
    double sum = 0;
    for (double value : lane)
      sum += value;
    return sum;
  }
};

/// body(i, l) for i in [0, count), l = i mod Lanes: the lane whose sums
/// index i adds to. The main loop's lanes are constants after unrolling, so
/// the sums stay in registers.
template <int64_t Lanes, typename Body>
inline void inLanes(int64_t count, Body &&body) {
  int64_t i = 0;
  for (; i + Lanes <= count; i += Lanes)
    for (int64_t l = 0; l < Lanes; ++l)
      body(i + l, l);
  for (int64_t l = 0; i < count; ++i, ++l)
    body(i, l);
}

} // namespace simit

#endif // SIMIT_LIB_RUNTIME_LANESUMS_H
