#include "metric/plane_bounds.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "metric/closest_point_triangle.h"

namespace meshdev {
namespace {

constexpr double kUnit = 0x1p-24;  // float's unit roundoff
constexpr float kInf = std::numeric_limits<float>::infinity();

// The planes of one triangle as the brute-force twin computes them, in double from the given
// corners: all zeros unless kappa <= kMaxCullKappa and |ab x ac|^2 >= kMinCullNormal2.
struct TwinPlanes {
  bool cullable = false;
  double n[3] = {}, d = 0, m[3][3] = {}, md[3] = {};
};
TwinPlanes twin_planes(const Vec3 v[3]) {
  TwinPlanes t;
  const Vec3 ab = v[1] - v[0], ac = v[2] - v[0], n = cross(ab, ac);
  const double kappa = norm(ab) * norm(ac) / norm(n);
  if (!(squared_norm(n) >= kMinCullNormal2 && kappa <= kMaxCullKappa)) return t;
  t.cullable = true;
  const Vec3 unit = (1.0 / norm(n)) * n;
  for (int a = 0; a < 3; ++a) t.n[a] = unit[a];
  t.d = dot(unit, v[0]);
  for (int e = 0; e < 3; ++e) {
    const Vec3 m = cross(v[(e + 1) % 3] - v[e], unit);
    const Vec3 mu = (1.0 / norm(m)) * m;
    for (int a = 0; a < 3; ++a) t.m[e][a] = mu[a];
    t.md[e] = dot(mu, v[e]);
  }
  return t;
}

// Candidates for one point: planes of random triangles (twin_planes), some all zeros (never
// culled), stored as kPlaneRows rows of `stride` floats with padding.
struct Candidates {
  std::vector<Vec3> corners;  // 3 per candidate
  std::vector<float> rows;
  std::size_t count = 0, stride = 0;
  double max_offset = 0;
};

Candidates make_candidates(std::mt19937_64& rng, std::size_t count) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Candidates c;
  c.count = count;
  c.stride = (count + kPlaneLanes - 1) / kPlaneLanes * kPlaneLanes;
  c.rows.assign(kPlaneRows * c.stride, 0.0f);
  for (std::size_t i = 0; i < c.stride; ++i) c.rows[kD * c.stride + i] = i < count ? 0.0f : -kInf;
  for (std::size_t i = 0; i < count; ++i) {
    const Vec3 centre{4 * u(rng), 4 * u(rng), 4 * u(rng)};
    Vec3 v[3];
    for (Vec3& x : v) x = centre + Vec3{u(rng), u(rng), u(rng)};
    c.corners.insert(c.corners.end(), v, v + 3);
    if (i % 7 == 3) continue;  // all zeros: bound 0
    const TwinPlanes t = twin_planes(v);
    auto put = [&](int row, const double* normal, double offset) {
      for (int a = 0; a < 3; ++a) c.rows[(row + a) * c.stride + i] = static_cast<float>(normal[a]);
      c.rows[(row + 3) * c.stride + i] = static_cast<float>(offset);
      c.max_offset = std::max(c.max_offset, std::fabs(offset));
    };
    put(kNx, t.n, t.d);
    for (int e = 0; e < 3; ++e) put(kM0x + 4 * e, t.m[e], t.md[e]);
  }
  return c;
}

// The brute-force runner-up: the smallest of bound[0 .. count) but at `first` (+inf if none).
float other_least(const float* bound, std::size_t count, std::size_t first) {
  float r = kInf;
  for (std::size_t i = 0; i < count; ++i)
    if (i != first) r = std::min(r, bound[i]);
  return r;
}

// The brute-force twin: the same formula in double from the same float coefficients.
double twin_bound(const Candidates& c, std::size_t i, const float q[3]) {
  auto plane = [&](int row) {
    double s = -static_cast<double>(c.rows[(row + 3) * c.stride + i]);
    for (int a = 0; a < 3; ++a) s += static_cast<double>(c.rows[(row + a) * c.stride + i]) * q[a];
    return s;
  };
  const double h = plane(kNx);
  const double o = std::max({plane(kM0x), plane(kM0x + 4), plane(kM0x + 8), 0.0});
  return h * h + o * o;
}

std::vector<SimdLevel> supported_levels() {
  std::vector<SimdLevel> levels;
  for (SimdLevel l : {SimdLevel::kBaseline, SimdLevel::kAvx2, SimdLevel::kAvx512})
    if (simd_supported(l)) levels.push_back(l);
  return levels;
}

TEST(PlaneBounds, EveryKernelEqualsTheDoubleTwinWithinTheMarginAndBoundsTheDistance) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-6.0, 6.0);
  for (SimdLevel level : supported_levels()) {
    SCOPED_TRACE(simd_level_name(level));
    const PlaneKernels& k = plane_kernels(level);
    for (std::size_t count : {1, 3, 4, 8, 15, 16, 17, 33, 64, 100}) {
      const Candidates c = make_candidates(rng, count);
      std::vector<float> bound(c.stride, -1.0f);
      std::vector<std::uint32_t> kept(c.stride);
      for (int trial = 0; trial < 20; ++trial) {
        const float q[3] = {static_cast<float>(u(rng)), static_cast<float>(u(rng)),
                            static_cast<float>(u(rng))};
        const Vec3 p{q[0], q[1], q[2]};
        const LeastBounds least_bounds = k.bounds(c.rows.data(), c.stride, count, q, bound.data());
        const std::size_t first = least_bounds.first;
        // The caller's margin (triangle_bvh.cpp, find_packet): 16 u (|q|_1 + max offset + 2).
        const double margin =
            16 * kUnit * (std::fabs(q[0]) + std::fabs(q[1]) + std::fabs(q[2]) + c.max_offset + 2);
        std::size_t least = 0;
        for (std::size_t i = 0; i < count; ++i) {
          const double twin = std::sqrt(twin_bound(c, i, q));
          ASSERT_NEAR(std::sqrt(static_cast<double>(bound[i])), twin, margin) << "candidate " << i;
          // A lower bound of the exact distance (all-zero planes: 0).
          const TriangleHit h = closest_point_on_triangle(p, c.corners[3 * i], c.corners[3 * i + 1],
                                                          c.corners[3 * i + 2]);
          EXPECT_LE(std::sqrt(static_cast<double>(bound[i])), std::sqrt(h.sq_distance) + margin);
          if (bound[i] < bound[least]) least = i;
        }
        EXPECT_EQ(first, least);  // the first of the smallest
        // The runner-up: the least of the others (candidates 3 and 10 both have bound 0: a tie
        // gives the smallest itself).
        EXPECT_EQ(least_bounds.runner_up, other_least(bound.data(), count, first));
        // Survivors: the brute-force filter, in index order, without `skip`.
        const float cutoff = bound[(first + 1) % count] * 1.5f;
        const std::size_t n = k.survivors(bound.data(), count, cutoff, first, kept.data());
        std::vector<std::uint32_t> expected;
        for (std::size_t i = 0; i < count; ++i)
          if (i != first && bound[i] <= cutoff) expected.push_back(static_cast<std::uint32_t>(i));
        EXPECT_EQ(std::vector<std::uint32_t>(kept.begin(), kept.begin() + n), expected);
      }
    }
  }
}

TEST(PlaneBounds, NanBoundsBecomeZeroAndPaddingIsNeverTaken) {
  for (SimdLevel level : supported_levels()) {
    SCOPED_TRACE(simd_level_name(level));
    const PlaneKernels& k = plane_kernels(level);
    std::mt19937_64 rng(3);
    Candidates c = make_candidates(rng, 5);
    c.rows[kNx * c.stride + 2] = std::numeric_limits<float>::quiet_NaN();
    std::vector<float> bound(c.stride);
    const float q[3] = {0.5f, -0.25f, 2.0f};
    const LeastBounds with_nan = k.bounds(c.rows.data(), c.stride, c.count, q, bound.data());
    EXPECT_EQ(with_nan.first, 2u);
    EXPECT_EQ(bound[2], 0.0f);
    EXPECT_EQ(with_nan.runner_up, other_least(bound.data(), c.count, 2));
    // Every real bound +inf: the first candidate, never a padding lane.
    for (std::size_t i = 0; i < c.count; ++i) c.rows[kD * c.stride + i] = -kInf;
    for (int r = 0; r < kPlaneRows; ++r)
      if (r != kD)
        for (std::size_t i = 0; i < c.count; ++i) c.rows[r * c.stride + i] = 0.0f;
    const LeastBounds all_inf = k.bounds(c.rows.data(), c.stride, c.count, q, bound.data());
    EXPECT_EQ(all_inf.first, 0u);
    EXPECT_EQ(all_inf.runner_up, kInf);
    std::vector<std::uint32_t> kept(c.stride);
    EXPECT_EQ(k.survivors(bound.data(), c.count, kInf, 99, kept.data()), c.count);
  }
}

TEST(PlaneBounds, BlockBoundsEqualTheRowBoundsBitForBit) {
  // The same coefficients as blocks of four lanes (BlockPlanes) and as rows: each level's
  // block_bounds over any subset of the blocks, in any order, gives the bits its `bounds` gives.
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-6.0, 6.0);
  for (SimdLevel level : supported_levels()) {
    SCOPED_TRACE(simd_level_name(level));
    const PlaneKernels& k = plane_kernels(level);
    for (std::size_t blocks : {1, 2, 3, 5, 8, 17, 64}) {
      Candidates c = make_candidates(rng, 4 * blocks);
      c.rows[kD * c.stride + 4 * (blocks - 1) + 3] = -kInf;  // an empty lane: +inf
      if (blocks > 2) c.rows[kM0x * c.stride + 5] = std::numeric_limits<float>::quiet_NaN();
      std::vector<BlockPlanes> planes(blocks);
      for (std::size_t b = 0; b < blocks; ++b)
        for (int r = 0; r < kPlaneRows; ++r)
          for (int lane = 0; lane < 4; ++lane)
            planes[b].row[r][lane] = c.rows[r * c.stride + 4 * b + lane];
      std::vector<float> by_rows(c.stride), by_blocks(4 * blocks + kPlaneLanes, -1.0f);
      for (int trial = 0; trial < 20; ++trial) {
        const float q[3] = {static_cast<float>(u(rng)), static_cast<float>(u(rng)),
                            static_cast<float>(u(rng))};
        k.bounds(c.rows.data(), c.stride, c.count, q, by_rows.data());
        // A subset of the blocks (odd sizes included), shuffled.
        std::vector<std::uint32_t> which(blocks);
        for (std::size_t b = 0; b < blocks; ++b) which[b] = static_cast<std::uint32_t>(b);
        std::shuffle(which.begin(), which.end(), rng);
        which.resize(1 + rng() % blocks);
        if (trial % 4 == 0) which.push_back(which.front());  // a block twice: its bounds tie
        std::vector<const BlockPlanes*> all;
        for (const BlockPlanes& b : planes) all.push_back(&b);
        const std::vector<std::uint8_t> chosen(which.begin(), which.end());
        const LeastBounds least_bounds =
            k.block_bounds(all.data(), chosen.data(), chosen.size(), q, by_blocks.data());
        const std::size_t first = least_bounds.first;
        std::size_t least = 0;
        for (std::size_t j = 0; j < which.size(); ++j)
          for (std::size_t lane = 0; lane < 4; ++lane) {
            const float want = by_rows[4 * which[j] + lane];
            const float got = by_blocks[4 * j + lane];
            ASSERT_EQ(std::memcmp(&got, &want, sizeof got), 0)
                << "block " << which[j] << " lane " << lane << ": " << got << " vs " << want;
            if (got < by_blocks[least]) least = 4 * j + lane;
          }
        EXPECT_EQ(first, least);  // the first of the smallest
        // The runner-up over the chosen blocks' lanes only (not an odd last block's copy).
        EXPECT_EQ(least_bounds.runner_up, other_least(by_blocks.data(), 4 * which.size(), first));
      }
    }
  }
}

TEST(PlaneBounds, EveryKernelsBlockPlanesEqualTheDoubleTwin) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (SimdLevel level : supported_levels()) {
    SCOPED_TRACE(simd_level_name(level));
    const PlaneKernels& k = plane_kernels(level);
    int never = 0, cullable = 0;
    for (int trial = 0; trial < 400; ++trial) {
      float corner[3][3][4] = {};
      Vec3 v[4][3];
      for (int lane = 0; lane < 4; ++lane) {
        const int kind = (trial + lane) % 8;  // 0-3 ordinary, then sliver, tiny, flat, empty
        const double size = std::pow(10.0, -4.0 * std::fabs(u(rng)));
        const Vec3 centre{u(rng), u(rng), u(rng)};
        for (Vec3& x : v[lane]) x = centre + size * Vec3{u(rng), u(rng), u(rng)};
        if (kind == 4) {  // a sliver near the origin (exact in float): kappa = 5e6
          v[lane][0] = Vec3{};
          v[lane][1] = Vec3{size, 0, 0};
          v[lane][2] = Vec3{0.5 * size, 1e-7 * size, 0};
        }
        if (kind == 5)
          for (Vec3& x : v[lane]) x = centre + 1e-6 * (x - centre);   // |n|^2 ~ 1e-24
        if (kind == 6) v[lane][2] = 0.5 * (v[lane][0] + v[lane][1]);  // no normal
        if (kind == 7)
          for (Vec3& x : v[lane]) x = Vec3{};  // an empty lane of a leaf block
        for (int c = 0; c < 3; ++c)
          for (int a = 0; a < 3; ++a) {
            corner[c][a][lane] = static_cast<float>(v[lane][c][a]);
            v[lane][c][a] = corner[c][a][lane];  // the float corners, exactly
          }
      }
      BlockPlanes out;
      std::memset(&out, 0x7f, sizeof out);  // every field must be written
      k.block_planes(corner, out);
      for (int lane = 0; lane < 4; ++lane) {
        SCOPED_TRACE("trial " + std::to_string(trial) + " lane " + std::to_string(lane));
        const TwinPlanes t = twin_planes(v[lane]);
        // Each value within a float step of the twin's (FMA rounds differently in double).
        auto near = [](float got, double want) {
          EXPECT_NEAR(got, want, 0x1p-23 * std::fabs(want) + 1e-12);
        };
        double max_offset = std::fabs(t.d);
        for (int a = 0; a < 3; ++a) near(out.row[kNx + a][lane], t.n[a]);
        near(out.row[kD][lane], t.d);
        for (int e = 0; e < 3; ++e) {
          for (int a = 0; a < 3; ++a) near(out.row[kM0x + 4 * e + a][lane], t.m[e][a]);
          near(out.row[kMd0 + 4 * e][lane], t.md[e]);
          max_offset = std::max(max_offset, std::fabs(t.md[e]));
        }
        if (!t.cullable) {  // all zeros: a bound of 0, never culled
          EXPECT_EQ(out.max_offset[lane], 0.0f);
          for (int r = 0; r < kPlaneRows; ++r) EXPECT_EQ(out.row[r][lane], 0.0f);
          ++never;
          continue;
        }
        ++cullable;
        // Rounded up: at least every offset the bound uses, at most a float step above.
        const float stored[4] = {out.row[kD][lane], out.row[kMd0][lane], out.row[kMd0 + 4][lane],
                                 out.row[kMd0 + 8][lane]};
        for (float f : stored) EXPECT_GE(out.max_offset[lane], std::fabs(f));
        EXPECT_GE(static_cast<double>(out.max_offset[lane]), max_offset * (1 - 1e-12));
        EXPECT_LE(static_cast<double>(out.max_offset[lane]), max_offset * (1 + 0x1p-22) + 1e-30);
      }
    }
    EXPECT_GE(never, 600);  // slivers, tiny, flat and empty lanes: half of them
    EXPECT_GE(cullable, 700);
  }
}

TEST(PlaneBounds, TheEnvironmentChoosesTheLevel) {
  const char* env = std::getenv("MESHDEV_SIMD");
  const std::string want = env != nullptr ? env : "";
  const SimdLevel level = simd_level();
  EXPECT_TRUE(simd_supported(level));
  if (want == "baseline") {
    EXPECT_EQ(level, SimdLevel::kBaseline);
  } else if (want == "avx512" && simd_supported(SimdLevel::kAvx512)) {
    EXPECT_EQ(level, SimdLevel::kAvx512);
  } else {  // AVX-512 only on request
    EXPECT_EQ(level, simd_supported(SimdLevel::kAvx2) ? SimdLevel::kAvx2 : SimdLevel::kBaseline);
  }
  std::printf("plane bounds: %s\n", simd_level_name(level));
}

}  // namespace
}  // namespace meshdev
