#pragma once
// A guard for requests that cannot fit in memory (a sample count or step typed wrong): refused
// up front, with what was asked and how much it needs, instead of a std::bad_alloc after the
// work before it, or the kernel's OOM killer (Linux overcommits: an allocation larger than the
// memory left succeeds, and the process is killed when it touches the pages).
#include <cstddef>
#include <string>

namespace meshdev {

// The memory a new allocation can still get, in bytes: the kernel's MemAvailable (free memory
// plus what it can reclaim, net of what this process and others already hold), or less where the
// cgroup's memory.max leaves less (a container's limit, less its memory.current); the machine's
// physical memory where /proc/meminfo cannot be read; 0 if none is known. It changes from call
// to call. O(1) (reads three small files).
std::size_t available_memory_bytes();

// Whether `bytes` fit in available_memory_bytes() (true where that is unknown). O(1).
bool fits_in_memory(double bytes);

// Throws InvalidInput "<what> need about X GiB, more than the Y GiB of memory available here;
// <advice>" if `bytes` (an estimate, as a double so that an absurd request cannot overflow it)
// exceeds available_memory_bytes(); does nothing where that is unknown. O(1).
void check_fits_in_memory(double bytes, const std::string& what, const std::string& advice);

}  // namespace meshdev
