//===--- CudaDriverTest.cpp - Loading the CUDA driver at run time ---------===//
//
// The reasons there is no device, each one line: a library that is not
// there, and one that is there but is not a CUDA driver. (A driver whose
// cuInit fails or that finds no device is tested with stand-in libraries
// in test/Run/GPU/no-device-reasons.test.)
//
//===----------------------------------------------------------------------===//

#include "simit/Runtime/CudaDriver.h"

#include "gtest/gtest.h"

using namespace simit::cuda;

namespace {
std::string message(llvm::Error err) { return llvm::toString(std::move(err)); }

TEST(CudaDriver, AbsentLibraryIsNamed) {
  auto driver = Driver::load("libsimit-absent-driver.so.1");
  ASSERT_FALSE(driver);
  std::string text = message(driver.takeError());
  EXPECT_EQ(text.rfind("libsimit-absent-driver.so.1 not found: ", 0), 0u)
      << text;
  EXPECT_EQ(text.find('\n'), std::string::npos) << text;
}

TEST(CudaDriver, LibraryWithoutTheDriverAPINamesTheFirstMissingFunction) {
  auto driver = Driver::load("libm.so.6");
  ASSERT_FALSE(driver);
  EXPECT_EQ(message(driver.takeError()),
            "libm.so.6 lacks the driver function cuInit");
}

TEST(CudaDriver, DeviceOpenReportsTheLoadFailure) {
  auto device = Device::open("libm.so.6");
  ASSERT_FALSE(device);
  EXPECT_EQ(message(device.takeError()),
            "libm.so.6 lacks the driver function cuInit");
}
} // namespace
