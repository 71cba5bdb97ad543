// Helpers shared by the tests.
#ifndef ANIMAT_TESTS_TEST_UTIL_H_
#define ANIMAT_TESTS_TEST_UTIL_H_

#include <cfenv>
#include <string>

namespace animat::testing {

// Disables floating-point traps for its lifetime (for tests that feed NaN
// or infinity on purpose), restoring them afterwards.
class FpTrapsOff {
 public:
  FpTrapsOff() : saved_(fegetexcept()) { fedisableexcept(FE_ALL_EXCEPT); }
  ~FpTrapsOff() {
    feclearexcept(FE_ALL_EXCEPT);
    feenableexcept(saved_);
  }
  FpTrapsOff(const FpTrapsOff&) = delete;
  FpTrapsOff& operator=(const FpTrapsOff&) = delete;

 private:
  int saved_;
};

// Path of a file in tests/data.
inline std::string TestData(const std::string& name) {
  return std::string(ANIMAT_TEST_DATA_DIR) + "/" + name;
}

}  // namespace animat::testing

#endif  // ANIMAT_TESTS_TEST_UTIL_H_
