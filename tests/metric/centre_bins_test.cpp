#include "metric/centre_bins.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "metric/plane_bounds.h"

namespace meshdev {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// A box whose centre key along every axis is `key` (lo = key / 2 - 1, hi = key / 2 + 1, exact
// for the keys used here), the other lanes as the build's records have them.
detail::FaceBox box_with_key(float key) {
  detail::FaceBox b{};
  for (int k = 0; k < 3; ++k) {
    b.lo[k] = key / 2 - 1;
    b.hi[k] = key / 2 + 1;
  }
  return b;
}

std::vector<std::uint8_t> bins_of(const std::vector<detail::FaceBox>& boxes, int axis, double lo,
                                  double scale, int bin_count, bool avx) {
  std::vector<std::uint8_t> bins(boxes.size() + 1, 0xab);
  const auto n = static_cast<std::uint32_t>(boxes.size());
  if (avx)
    detail::centre_bins_avx2(boxes.data(), n, axis, lo, scale, bin_count, bins.data());
  else
    detail::centre_bins(boxes.data(), n, axis, lo, scale, bin_count, bins.data());
  EXPECT_EQ(bins.back(), 0xab) << "written past count";
  bins.pop_back();
  return bins;
}

// Keys spread over [lo, lo + 16 / scale] land in 16 bins: the bin of a key is how many bin
// boundaries lo + k / scale (k = 1 .. 15) it reaches, keys at or below lo are in bin 0 and keys
// at or beyond the last boundary in bin 15; bins never decrease with the key.
TEST(CentreBins, BinsAreTheBoundariesReached) {
  const double lo = -3.0, scale = 16.0 / 8.0;  // bins 0.5 wide over [-3, 5]
  std::vector<detail::FaceBox> boxes;
  std::vector<int> expected;
  for (int q = -20; q <= 60; ++q) {  // keys -8 .. 12 in steps of 0.25: on and between boundaries
    const float key = 0.25f * static_cast<float>(q) - 3.0f;
    boxes.push_back(box_with_key(key));
    int reached = 0;
    for (int k = 1; k < 16; ++k) reached += key >= lo + k / scale;
    expected.push_back(reached);
  }
  for (bool avx : {false, true}) {
    if (avx && simd_level() == SimdLevel::kBaseline) continue;
    for (int axis = 0; axis < 3; ++axis) {
      const std::vector<std::uint8_t> bins = bins_of(boxes, axis, lo, scale, 16, avx);
      for (std::size_t i = 0; i < boxes.size(); ++i) {
        EXPECT_EQ(bins[i], expected[i]) << "face " << i << " axis " << axis << " avx " << avx;
        if (i > 0) {
          EXPECT_LE(bins[i - 1], bins[i]);
        }
      }
    }
  }
}

// A NaN key (a box reaching -inf and +inf) counts as 0; an infinite key goes to an end bin; a
// NaN t (scale 0 times an infinite difference) to bin 0.
TEST(CentreBins, NaNAndInfiniteKeys) {
  detail::FaceBox nan_box{}, far_box{}, near_box{};
  for (int k = 0; k < 3; ++k) {
    nan_box.lo[k] = -kInf, nan_box.hi[k] = kInf;
    far_box.lo[k] = 1.0f, far_box.hi[k] = kInf;
    near_box.lo[k] = -kInf, near_box.hi[k] = 1.0f;
  }
  const std::vector<detail::FaceBox> boxes = {nan_box, far_box, near_box, nan_box, far_box};
  for (bool avx : {false, true}) {
    if (avx && simd_level() == SimdLevel::kBaseline) continue;
    // lo -1, 4 bins per unit: key 0 is t = 4.
    EXPECT_EQ(bins_of(boxes, 1, -1.0, 4.0, 16, avx), (std::vector<std::uint8_t>{4, 15, 0, 4, 15}));
    EXPECT_EQ(bins_of(boxes, 2, -kInf, 0.0, 16, avx), (std::vector<std::uint8_t>{0, 0, 0, 0, 0}));
  }
}

// The AVX2 version equals the baseline on random boxes: every count up to 67 (the four-lane loop
// and its tail), every axis, bin counts 1 to 256, keys below, inside and beyond the range, NaN
// boxes among them.
TEST(CentreBins, BothVersionsAgree) {
  if (simd_level() == SimdLevel::kBaseline) GTEST_SKIP() << "this CPU runs no AVX2";
  std::mt19937 rng(44);
  std::uniform_real_distribution<float> coord(-2.0f, 2.0f);
  const int bin_counts[] = {1, 2, 16, 255, 256};
  for (int round = 0; round < 3000; ++round) {
    const auto n = static_cast<std::size_t>(round % 68);
    std::vector<detail::FaceBox> boxes(n);
    for (detail::FaceBox& b : boxes)
      for (int k = 0; k < 4; ++k) {
        const float a = coord(rng), c = coord(rng);
        b.lo[k] = std::min(a, c), b.hi[k] = std::max(a, c);
        if (rng() % 50 == 0) b.lo[k] = -kInf, b.hi[k] = rng() % 2 ? kInf : kNaN;
      }
    const int axis = round % 3;
    const int bin_count = bin_counts[round % 5];
    const double lo = -3.0 + static_cast<double>(rng() % 100) / 50.0;
    const double scale = bin_count / (0.5 + static_cast<double>(rng() % 100) / 20.0);
    EXPECT_EQ(bins_of(boxes, axis, lo, scale, bin_count, true),
              bins_of(boxes, axis, lo, scale, bin_count, false))
        << "round " << round;
  }
}

}  // namespace
}  // namespace meshdev
