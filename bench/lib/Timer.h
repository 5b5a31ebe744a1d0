//===--- Timer.h - Wall-clock milliseconds ---------------------*- C++ -*-===//

#ifndef SIMIT_BENCH_TIMER_H
#define SIMIT_BENCH_TIMER_H

#include <chrono>

namespace simit::bench {

class Timer {
public:
  Timer() : start_(std::chrono::steady_clock::now()) {}
  /// Milliseconds since construction or the previous lap.
  double lapMs() {
    auto now = std::chrono::steady_clock::now();
    double ms = std::chrono::duration<double, std::milli>(now - start_).count();
    start_ = now;
    return ms;
  }

private:
  std::chrono::steady_clock::time_point start_;
};

} // namespace simit::bench

#endif // SIMIT_BENCH_TIMER_H
