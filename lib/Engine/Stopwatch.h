//===--- Stopwatch.h - Milliseconds between two points --------------------===//

#ifndef SIMIT_LIB_ENGINE_STOPWATCH_H
#define SIMIT_LIB_ENGINE_STOPWATCH_H

#include <chrono>

namespace simit {

/// Measures wall time from its construction (or the last restart).
class Stopwatch {
public:
  double milliseconds() const {
    return std::chrono::duration<double, std::milli>(Clock::now() - start)
        .count();
  }
  void restart() { start = Clock::now(); }

private:
  using Clock = std::chrono::steady_clock;
  Clock::time_point start = Clock::now();
};

} // namespace simit

#endif // SIMIT_LIB_ENGINE_STOPWATCH_H
