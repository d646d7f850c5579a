#include "metric/memory_limit.h"

#include <unistd.h>

#include <fstream>
#include <sstream>

#include "metric/errors.h"

namespace meshdev {
namespace {

// The number after `key` in /proc/meminfo, in bytes (the file gives kB); 0 if absent.
std::size_t meminfo_bytes(const std::string& key) {
  std::ifstream in("/proc/meminfo");
  std::string name, unit;
  unsigned long long kb = 0;
  while (in >> name >> kb) {
    std::getline(in, unit);
    if (name == key + ":") return static_cast<std::size_t>(kb) * 1024;
  }
  return 0;
}

// A number of bytes read from a cgroup v2 file; 0 if the file is missing or says "max".
unsigned long long cgroup_bytes(const char* file) {
  std::ifstream in(file);
  unsigned long long bytes = 0;
  return in >> bytes ? bytes : 0;
}

// The one test behind fits_in_memory and check_fits_in_memory (0: unknown, anything fits).
bool fits(double bytes, std::size_t available) {
  return available == 0 || !(bytes > static_cast<double>(available));
}

}  // namespace

std::size_t available_memory_bytes() {
  std::size_t bytes = meminfo_bytes("MemAvailable");
  if (bytes == 0) {
    const long pages = sysconf(_SC_PHYS_PAGES);
    const long page = sysconf(_SC_PAGE_SIZE);
    if (pages > 0 && page > 0)
      bytes = static_cast<std::size_t>(pages) * static_cast<std::size_t>(page);
  }
  const unsigned long long limit = cgroup_bytes("/sys/fs/cgroup/memory.max");
  if (limit > 0) {
    const unsigned long long used = cgroup_bytes("/sys/fs/cgroup/memory.current");
    const auto left = static_cast<std::size_t>(limit > used ? limit - used : 0);
    if (bytes == 0 || left < bytes) bytes = left;
  }
  return bytes;
}

bool fits_in_memory(double bytes) {
  return fits(bytes, available_memory_bytes());
}

void check_fits_in_memory(double bytes, const std::string& what, const std::string& advice) {
  const std::size_t available = available_memory_bytes();
  if (fits(bytes, available)) return;
  constexpr double kGiB = 1024.0 * 1024.0 * 1024.0;
  std::ostringstream m;
  m.precision(3);
  m << what << " need about " << bytes / kGiB << " GiB, more than the "
    << static_cast<double>(available) / kGiB << " GiB of memory available here; " << advice;
  throw InvalidInput(m.str());
}

}  // namespace meshdev
