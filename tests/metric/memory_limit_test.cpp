#include "metric/memory_limit.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <string>

#include "metric/errors.h"

namespace meshdev {
namespace {

// The memory available is known on Linux (/proc/meminfo), at most the machine's, and a request
// well within it passes (half of it: the figure moves as other processes allocate).
TEST(MemoryLimit, AvailableMemoryIsKnownAndARequestWithinItFits) {
  const std::size_t available = available_memory_bytes();
  ASSERT_GT(available, std::size_t{1} << 20);
  EXPECT_LE(available, static_cast<std::size_t>(sysconf(_SC_PHYS_PAGES)) *
                           static_cast<std::size_t>(sysconf(_SC_PAGE_SIZE)));
  EXPECT_TRUE(fits_in_memory(1.0));
  EXPECT_NO_THROW(check_fits_in_memory(1.0, "one byte", "-"));
  EXPECT_NO_THROW(check_fits_in_memory(0.5 * static_cast<double>(available), "half of it", "-"));
}

// A request beyond it is refused with what was asked, what it needs, and the advice; so is one
// too large for any size_t (the estimate is a double).
TEST(MemoryLimit, ARequestBeyondItIsRefusedWithWhatItNeeds) {
  const double available = static_cast<double>(available_memory_bytes());
  ASSERT_GT(available, 0.0);
  try {
    check_fits_in_memory(2.0 * available, "the widgets", "ask for fewer widgets");
    FAIL() << "no exception";
  } catch (const InvalidInput& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("the widgets need about "), std::string::npos) << m;
    EXPECT_NE(m.find(" GiB of memory available here"), std::string::npos) << m;
    EXPECT_NE(m.find("; ask for fewer widgets"), std::string::npos) << m;
  }
  EXPECT_FALSE(fits_in_memory(2.0 * available));
  EXPECT_THROW(check_fits_in_memory(1e300, "x", "y"), InvalidInput);
}

}  // namespace
}  // namespace meshdev
