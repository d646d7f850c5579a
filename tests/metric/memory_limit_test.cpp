#include "metric/memory_limit.h"

#include <gtest/gtest.h>

#include <string>

#include "metric/errors.h"

namespace meshdev {
namespace {

// The memory here is known on Linux (sysconf), and a request within it passes.
TEST(MemoryLimit, UsableMemoryIsKnownAndASmallRequestFits) {
  const std::size_t usable = usable_memory_bytes();
  ASSERT_GT(usable, std::size_t{1} << 20);
  EXPECT_NO_THROW(check_fits_in_memory(1.0, "one byte", "-"));
  EXPECT_NO_THROW(check_fits_in_memory(0.5 * static_cast<double>(usable), "half of it", "-"));
}

// A request beyond it is refused with what was asked, what it needs, and the advice; so is one
// too large for any size_t (the estimate is a double).
TEST(MemoryLimit, ARequestBeyondItIsRefusedWithWhatItNeeds) {
  const double usable = static_cast<double>(usable_memory_bytes());
  ASSERT_GT(usable, 0.0);
  try {
    check_fits_in_memory(2.0 * usable, "the widgets", "ask for fewer widgets");
    FAIL() << "no exception";
  } catch (const InvalidInput& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("the widgets need about "), std::string::npos) << m;
    EXPECT_NE(m.find(" GiB, more than the "), std::string::npos) << m;
    EXPECT_NE(m.find("; ask for fewer widgets"), std::string::npos) << m;
  }
  EXPECT_THROW(check_fits_in_memory(1e300, "x", "y"), InvalidInput);
}

}  // namespace
}  // namespace meshdev
