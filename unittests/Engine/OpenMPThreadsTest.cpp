//===- OpenMPThreadsTest.cpp - The process's OpenMP thread cap ------------===//
//
// CHOLMOD's loops ask for 4 threads with a num_threads clause; after
// capOpenMPThreads(1) such a region (through the GOMP entry point CHOLMOD
// calls, which libomp serves) runs on one thread. One process per test
// (CTest), so the cap is this test's alone.
//
//===----------------------------------------------------------------------===//

#include "simit/Runtime/OpenMPThreads.h"

#include "gtest/gtest.h"

#include <atomic>
#include <cstdlib>

extern "C" {
void GOMP_parallel(void (*body)(void *), void *data, unsigned threads,
                   unsigned flags);
int omp_get_num_threads(void);
}

namespace {

void recordTeamSize(void *size) {
  static_cast<std::atomic<int> *>(size)->store(omp_get_num_threads());
}

TEST(OpenMPThreadsTest, CapsRegionsAskingForMoreThreads) {
  // A limit in the environment wins: no cap is set.
  if (std::getenv("OMP_THREAD_LIMIT") ||
      std::getenv("KMP_DEVICE_THREAD_LIMIT") ||
      std::getenv("KMP_ALL_THREADS")) {
    EXPECT_EQ(simit::capOpenMPThreads(1), 0);
    return;
  }
  ASSERT_EQ(simit::capOpenMPThreads(1), 1);
  // Only the first cap counts.
  EXPECT_EQ(simit::capOpenMPThreads(3), 1);
  std::atomic<int> teamSize{0};
  GOMP_parallel(recordTeamSize, &teamSize, 4, 0);
  EXPECT_EQ(teamSize.load(), 1);
}

TEST(OpenMPThreadsTest, AvailableCoresIsPositive) {
  EXPECT_GE(simit::availableCores(), 1);
}

} // namespace
