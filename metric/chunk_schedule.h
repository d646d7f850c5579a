#pragma once
// The chunks of a parallel loop dealt to a team so that each thread walks one contiguous range:
// thread t takes the chunks of the t-th of `team` equal ranges from the front, one at a time, and
// a thread whose range is spent takes single chunks from the back of the range with the most left.
// For loops whose consecutive chunks touch the same data (the deviation loop's chunks follow the
// sampler's path over the surface, so neighbouring chunks query the same part of B): each thread
// keeps its caches, the per-thread ones (the BVH's plane cache) and its core's, on its own part,
// where OpenMP's schedule(dynamic, 1) dealt neighbouring chunks to different threads, which then
// fetched and prepared the same data twice; the stealing keeps dynamic's balance where chunks
// differ in cost. docs/performance.md §3.2 has what it bought.
#include <atomic>
#include <cstdint>
#include <memory>

namespace meshdev {

class ChunkSchedule {
 public:
  // Chunks 0 .. chunks - 1 for threads 0 .. team - 1. Preconditions: 0 <= chunks < 2^32,
  // team >= 1. O(team).
  ChunkSchedule(std::int64_t chunks, int team);

  // The next chunk for `thread` (0 <= thread < team), or -1 once every chunk has been taken: the
  // first untaken chunk of its own range, else the last untaken chunk of the range with the most
  // untaken chunks. Over all calls from all threads, each chunk is returned exactly once; a
  // thread's chunks from its own range come in increasing order. Thread-safe and lock-free (one
  // compare-and-swap per chunk without contention). O(1), O(team) once the own range is spent.
  std::int64_t next(int thread);

 private:
  // The untaken chunks [front, back) of one thread's range, as front << 32 | back, alone on its
  // cache line (the owner takes from the front, the others from the back).
  struct alignas(64) Range {
    std::atomic<std::uint64_t> span{0};
  };
  std::unique_ptr<Range[]> ranges_;
  int team_;
};

}  // namespace meshdev
