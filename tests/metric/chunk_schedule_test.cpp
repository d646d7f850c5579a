#include "metric/chunk_schedule.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <thread>
#include <vector>

namespace meshdev {
namespace {

// Every chunk next() gives `thread` until it says none is left.
std::vector<std::int64_t> drain(ChunkSchedule& schedule, int thread) {
  std::vector<std::int64_t> got;
  for (std::int64_t c; (c = schedule.next(thread)) >= 0;) got.push_back(c);
  return got;
}

TEST(ChunkSchedule, OneThreadTakesEveryChunkInOrder) {
  ChunkSchedule schedule(7, 1);
  EXPECT_EQ(drain(schedule, 0), (std::vector<std::int64_t>{0, 1, 2, 3, 4, 5, 6}));
  EXPECT_EQ(schedule.next(0), -1);  // and stays spent
}

TEST(ChunkSchedule, NoChunks) {
  ChunkSchedule schedule(0, 3);
  for (int t = 0; t < 3; ++t) EXPECT_EQ(schedule.next(t), -1);
}

TEST(ChunkSchedule, OwnRangeFromTheFrontThenTheFullestRangeFromTheBack) {
  // Ten chunks for three threads: ranges [0, 3), [3, 6), [6, 10). Thread 1 alone takes its own,
  // then always the last chunk of the range with the most left (the first such range on a tie).
  ChunkSchedule schedule(10, 3);
  EXPECT_EQ(drain(schedule, 1), (std::vector<std::int64_t>{3, 4, 5, 9, 2, 8, 1, 7, 0, 6}));
}

TEST(ChunkSchedule, ThiefAndOwnerShareARangeWithoutOverlap) {
  ChunkSchedule schedule(8, 2);  // [0, 4), [4, 8)
  EXPECT_EQ(schedule.next(0), 0);
  EXPECT_EQ(drain(schedule, 1), (std::vector<std::int64_t>{4, 5, 6, 7, 3, 2, 1}));
  EXPECT_EQ(schedule.next(0), -1);
}

TEST(ChunkSchedule, MoreThreadsThanChunks) {
  ChunkSchedule schedule(2, 5);
  std::vector<std::int64_t> all;
  for (int t = 0; t < 5; ++t)
    for (std::int64_t c : drain(schedule, t)) all.push_back(c);
  std::sort(all.begin(), all.end());
  EXPECT_EQ(all, (std::vector<std::int64_t>{0, 1}));
}

TEST(ChunkSchedule, ConcurrentThreadsGetEachChunkExactlyOnce) {
  // Threads of unequal speed (the slow ones yield after every chunk) so that ranges are stolen
  // from while their owners still take from them.
  constexpr std::int64_t kChunks = 20000;
  constexpr int kTeam = 4;
  for (int round = 0; round < 5; ++round) {
    ChunkSchedule schedule(kChunks, kTeam);
    std::vector<std::vector<std::int64_t>> got(kTeam);
    std::vector<std::thread> team;
    for (int t = 0; t < kTeam; ++t)
      team.emplace_back([&, t] {
        for (std::int64_t c; (c = schedule.next(t)) >= 0;) {
          got[t].push_back(c);
          if (t % 2 == 1) std::this_thread::yield();
        }
      });
    for (std::thread& th : team) th.join();
    std::vector<int> taken(kChunks, 0);
    for (int t = 0; t < kTeam; ++t) {
      // Its own range's chunks (the t-th quarter) in increasing order.
      const std::int64_t lo = t * kChunks / kTeam, hi = (t + 1) * kChunks / kTeam;
      std::int64_t last = -1;
      for (std::int64_t c : got[t]) {
        ASSERT_GE(c, 0);
        ASSERT_LT(c, kChunks);
        ++taken[static_cast<std::size_t>(c)];
        if (c >= lo && c < hi) {
          EXPECT_GT(c, last);
          last = c;
        }
      }
    }
    EXPECT_EQ(std::count(taken.begin(), taken.end(), 1), kChunks) << "round " << round;
  }
}

}  // namespace
}  // namespace meshdev
