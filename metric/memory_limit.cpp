#include "metric/memory_limit.h"

#include <unistd.h>

#include <fstream>
#include <sstream>

#include "metric/errors.h"

namespace meshdev {

std::size_t usable_memory_bytes() {
  std::size_t bytes = 0;
  const long pages = sysconf(_SC_PHYS_PAGES);
  const long page = sysconf(_SC_PAGE_SIZE);
  if (pages > 0 && page > 0)
    bytes = static_cast<std::size_t>(pages) * static_cast<std::size_t>(page);
  // cgroup v2: "max" (no limit) or a number of bytes.
  std::ifstream in("/sys/fs/cgroup/memory.max");
  unsigned long long limit = 0;
  if (in >> limit && limit > 0 && (bytes == 0 || limit < bytes))
    bytes = static_cast<std::size_t>(limit);
  return bytes;
}

void check_fits_in_memory(double bytes, const std::string& what, const std::string& advice) {
  const std::size_t usable = usable_memory_bytes();
  if (usable == 0 || !(bytes > static_cast<double>(usable))) return;
  constexpr double kGiB = 1024.0 * 1024.0 * 1024.0;
  std::ostringstream m;
  m.precision(3);
  m << what << " need about " << bytes / kGiB << " GiB, more than the "
    << static_cast<double>(usable) / kGiB << " GiB of memory here; " << advice;
  throw InvalidInput(m.str());
}

}  // namespace meshdev
