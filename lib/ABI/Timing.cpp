//===--- Timing.cpp - clock, storeTime and the phase timer ----------------===//

#include "simit/ABI/RuntimeFunctions.h"

#include <chrono>

// clock(): a monotonic timestamp in microseconds. storeTime(slot, value)
// records a value in a host slot (slots 0..63); its result is 0.
extern "C" double simit_rt_clock() {
  using namespace std::chrono;
  return static_cast<double>(
      duration_cast<microseconds>(steady_clock::now().time_since_epoch())
          .count());
}

static double storedTimes[64];

extern "C" double simit_rt_storeTime(int32_t slot, double value) {
  if (slot >= 0 && slot < 64)
    storedTimes[slot] = value;
  return 0.0;
}

// The phase timer of simit-time-phases: begin/end pairs never nest, and a
// program's functions run one at a time.
static std::chrono::steady_clock::time_point phaseStart[2];
static double phaseMilliseconds[2];

extern "C" void simit_rt_phase_begin(int32_t phase) {
  if (phase >= 0 && phase < 2)
    phaseStart[phase] = std::chrono::steady_clock::now();
}

extern "C" void simit_rt_phase_end(int32_t phase) {
  if (phase >= 0 && phase < 2)
    phaseMilliseconds[phase] +=
        std::chrono::duration<double, std::milli>(
            std::chrono::steady_clock::now() - phaseStart[phase])
            .count();
}

simit::PhaseTimes simit::readPhaseTimes() {
  return {phaseMilliseconds[0], phaseMilliseconds[1]};
}

void simit::resetPhaseTimes() {
  phaseMilliseconds[0] = phaseMilliseconds[1] = 0.0;
}
