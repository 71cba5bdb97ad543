// Test entry point: floating-point traps on, so an invalid operation or a
// division by zero fails the test where it happens (Jolt's habit). Tests
// that create NaN on purpose use FpTrapsOff (test_util.h).
#include <cfenv>

#include <gtest/gtest.h>

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  feenableexcept(FE_INVALID | FE_DIVBYZERO | FE_OVERFLOW);
  return RUN_ALL_TESTS();
}
