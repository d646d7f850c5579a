#include "metric/query_frame.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

namespace meshdev {
namespace {

using detail::FrameMap;
using detail::PacketExtent;

template <typename T>
bool same_bits(T a, T b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

// What one version of the packet's framing wrote.
struct Framed {
  std::size_t taken = 0;
  float qf[64][3];
  double slack[64];
  float lo[3] = {7.0f, 7.0f, 7.0f}, hi[3] = {7.0f, 7.0f, 7.0f};  // "untouched" marker
};

Framed frame(bool scalar, const std::vector<Vec3>& points, const FrameMap& map, double corner_error,
             const PacketExtent& extent) {
  Framed f;
  const std::size_t count = points.size() < 64 ? points.size() : 64;
  f.taken = scalar ? detail::frame_packet_scalar(points.data(), count, map, corner_error, extent,
                                                 f.qf, f.slack, f.lo, f.hi)
                   : detail::frame_packet(points.data(), count, map, corner_error, extent, f.qf,
                                          f.slack, f.lo, f.hi);
  return f;
}

// The two versions agree bit for bit on what they take: count, coordinates, slack and box.
void expect_same(const Framed& a, const Framed& b) {
  ASSERT_EQ(a.taken, b.taken);
  for (std::size_t k = 0; k < a.taken; ++k)
    for (int axis = 0; axis < 3; ++axis) {
      EXPECT_TRUE(same_bits(a.qf[k][axis], b.qf[k][axis])) << "query " << k << " axis " << axis;
      EXPECT_TRUE(same_bits(a.slack[k], b.slack[k])) << "query " << k;
    }
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_TRUE(same_bits(a.lo[axis], b.lo[axis])) << "axis " << axis;
    EXPECT_TRUE(same_bits(a.hi[axis], b.hi[axis])) << "axis " << axis;
  }
}

TEST(QueryFrame, FrameQueryRoundsAndBoundsTheRounding) {
  const FrameMap map{{1.0, -2.0, 0.5}, 0.25};
  const Vec3 p{3.1, 0.7, -9.3};
  float qf[3];
  double slack = 0.0;
  ASSERT_TRUE(detail::frame_query(p, map, 1e-7, qf, slack));
  double rounding = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double q = (p[k] - map.origin[k]) * map.scale;
    EXPECT_EQ(qf[k], static_cast<float>(q));
    rounding += std::fabs(static_cast<double>(qf[k]) - q);
  }
  EXPECT_GE(slack, 1e-7 + rounding);
  EXPECT_LE(slack, 1e-7 + rounding + 1e-14);
  // NaN and far-out queries are not culled; their slack is the corners' alone.
  EXPECT_FALSE(detail::frame_query({std::nan(""), 0, 0}, map, 1e-7, qf, slack));
  EXPECT_EQ(slack, 1e-7);
  EXPECT_FALSE(detail::frame_query({0, 0, 1e13}, map, 1e-7, qf, slack));
  EXPECT_TRUE(detail::frame_query({0, 0, 1e12}, map, 1e-7, qf, slack));  // 0.25e12 in the frame
}

TEST(QueryFrame, PacketTakesQueriesWhileTheBoxFits) {
  const FrameMap map{{0, 0, 0}, 1.0};
  // Along x, 0.1 apart: the box's squared diagonal is 0.01 (k)^2 after k + 1 queries.
  std::vector<Vec3> points;
  for (int k = 0; k < 40; ++k) points.push_back({0.1 * k, 0.0, 0.0});
  for (bool scalar : {false, true}) {
    SCOPED_TRACE(scalar ? "scalar" : "SSE2");
    // Up to 0.2: five queries (0 .. 0.4); the sixth would span 0.5.
    Framed f = frame(scalar, points, map, 0.0, {0.2, 0.2, 64});
    EXPECT_EQ(f.taken, 5u);
    EXPECT_EQ(f.lo[0], 0.0f);
    EXPECT_EQ(f.hi[0], static_cast<float>(0.4));
    // A tighter limit from the third query on: three queries (the third spans 0.2).
    f = frame(scalar, points, map, 0.0, {0.25, 0.041, 2});
    EXPECT_EQ(f.taken, 3u);
    // The count caps it.
    f = frame(scalar, points, map, 0.0, {1e9, 1e9, 64});
    EXPECT_EQ(f.taken, 40u);
    // A query that cannot be culled ends the packet; the first one gives an empty packet whose
    // box is left as it was.
    std::vector<Vec3> bad = points;
    bad[3].y = std::numeric_limits<double>::infinity();
    EXPECT_EQ(frame(scalar, bad, map, 0.0, {1e9, 1e9, 64}).taken, 3u);
    bad[0].z = std::nan("");
    f = frame(scalar, bad, map, 0.0, {1e9, 1e9, 64});
    EXPECT_EQ(f.taken, 0u);
    EXPECT_EQ(f.lo[0], 7.0f);
    EXPECT_EQ(f.hi[2], 7.0f);
  }
}

TEST(QueryFrame, SseVersionMatchesTheScalarOneBitForBit) {
  std::mt19937_64 rng(46);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), spread(0.0, 0.05);
  std::uniform_int_distribution<int> pick(0, 19);
  for (int trial = 0; trial < 400; ++trial) {
    FrameMap map{{unit(rng), unit(rng), unit(rng)}, std::ldexp(1.0, pick(rng) - 10)};
    if (trial % 4 == 0) map.origin[0] = map.origin[1] = map.origin[2] = 0.0;
    const double corner_error = std::ldexp(unit(rng) + 1.0, -30);
    // A walk of nearby points, as a sampler's sorted samples are, with signed zeros in the
    // frame, points beyond the cull range and NaN now and then.
    std::vector<Vec3> points;
    Vec3 p{unit(rng), unit(rng), unit(rng)};
    for (int k = 0; k < 64; ++k) {
      p = {p.x + spread(rng) * unit(rng), p.y + spread(rng) * unit(rng),
           p.z + spread(rng) * unit(rng)};
      Vec3 q = p;
      const int kind = pick(rng);
      if (kind == 0) q.x = map.origin[0];                   // +0 in the frame
      if (kind == 1) q.x = -0.0;                            // -0 where the origin is 0
      if (kind == 2) q.x = 0.0;                             // ... and +0
      if (kind == 3 && trial % 8 == 2) q.z = 1e15;          // too far out to cull
      if (kind == 4 && trial % 8 == 3) q.y = std::nan("");  // NaN
      points.push_back(q);
    }
    const double d = std::ldexp(1.0, pick(rng) - 12);
    const PacketExtent extent{d * d, 0.25 * d * d, static_cast<std::size_t>(pick(rng) + 4)};
    SCOPED_TRACE(testing::Message() << "trial " << trial);
    expect_same(frame(false, points, map, corner_error, extent),
                frame(true, points, map, corner_error, extent));
  }
}

}  // namespace
}  // namespace meshdev
