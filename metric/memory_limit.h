#pragma once
// A guard for requests that cannot fit in memory (a sample count or step typed wrong): refused
// up front, with what was asked and how much it needs, instead of a std::bad_alloc after the
// work before it, or the kernel's OOM killer (Linux overcommits: an allocation larger than the
// memory left succeeds, and the process is killed when it touches the pages).
#include <cstddef>
#include <string>

namespace meshdev {

// The memory this process may use, in bytes: the machine's physical memory (sysconf), or the
// cgroup's memory.max where that is smaller (a container's limit); 0 if neither is known. O(1)
// (reads one small file).
std::size_t usable_memory_bytes();

// Throws InvalidInput "<what> need about X GiB, more than the Y GiB of memory here; <advice>"
// if `bytes` (an estimate, as a double so that an absurd request cannot overflow it) exceeds
// usable_memory_bytes(); does nothing where that is unknown. O(1).
void check_fits_in_memory(double bytes, const std::string& what, const std::string& advice);

}  // namespace meshdev
