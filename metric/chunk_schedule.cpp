#include "metric/chunk_schedule.h"

#include <cassert>

namespace meshdev {
namespace {

constexpr std::uint64_t pack(std::uint64_t front, std::uint64_t back) {
  return front << 32 | back;
}
constexpr std::uint64_t front_of(std::uint64_t span) {
  return span >> 32;
}
constexpr std::uint64_t back_of(std::uint64_t span) {
  return span & 0xffffffffu;
}

}  // namespace

ChunkSchedule::ChunkSchedule(std::int64_t chunks, int team)
    : ranges_(std::make_unique<Range[]>(static_cast<std::size_t>(team))), team_(team) {
  assert(chunks >= 0 && chunks < (std::int64_t{1} << 32) && team >= 1);
  const auto n = static_cast<std::uint64_t>(chunks);
  const auto t = static_cast<std::uint64_t>(team);
  for (std::uint64_t k = 0; k < t; ++k)
    ranges_[k].span.store(pack(k * n / t, (k + 1) * n / t), std::memory_order_relaxed);
}

std::int64_t ChunkSchedule::next(int thread) {
  assert(thread >= 0 && thread < team_);
  // Relaxed order: a chunk's number is all a thread learns from the schedule; the loop's data
  // is ordered by the parallel region around it.
  std::atomic<std::uint64_t>& own = ranges_[thread].span;
  std::uint64_t span = own.load(std::memory_order_relaxed);
  while (front_of(span) < back_of(span))
    if (own.compare_exchange_weak(span, span + pack(1, 0), std::memory_order_relaxed))
      return static_cast<std::int64_t>(front_of(span));
  for (;;) {  // the own range is spent: the back of the fullest other one
    int victim = -1;
    std::uint64_t most = 0;
    for (int k = 0; k < team_; ++k) {
      const std::uint64_t s = ranges_[k].span.load(std::memory_order_relaxed);
      if (back_of(s) - front_of(s) > most) {  // front <= back always
        most = back_of(s) - front_of(s);
        victim = k;
      }
    }
    if (victim < 0) return -1;
    std::atomic<std::uint64_t>& other = ranges_[victim].span;
    span = other.load(std::memory_order_relaxed);
    while (front_of(span) < back_of(span))
      if (other.compare_exchange_weak(span, span - 1, std::memory_order_relaxed))
        return static_cast<std::int64_t>(back_of(span) - 1);
  }
}

}  // namespace meshdev
