#include "metric/face_boxes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "metric/mesh.h"
#include "metric/plane_bounds.h"
#include "tests/support/shapes.h"

namespace meshdev {
namespace {

bool same_bits(const void* a, const void* b, std::size_t bytes) {
  return std::memcmp(a, b, bytes) == 0;
}

// Both versions give the same records and bounds, bit for bit, for ranges of every length modulo
// 4 (the AVX2 version's last faces go one at a time), in frames where the coordinates reach past
// float's range, and on vertices at +-inf and NaN (which a validated mesh never has, but the two
// must still agree on); the corners' bounds are equal.
TEST(FaceBoxes, BothVersionsGiveTheSameRecordsBitForBit) {
  if (simd_level() == SimdLevel::kBaseline) GTEST_SKIP() << "this CPU runs no AVX2";
  std::mt19937_64 rng(5);
  TriMesh soup = test::kernel_soup(3000, 5);
  const double inf = std::numeric_limits<double>::infinity();
  for (std::uint32_t v : {100u, 101u, 700u}) soup.positions[v].x = inf;
  soup.positions[1300].y = -inf;
  // NaN at a first corner (a NaN at the others is dropped by std::min and std::max) of face 1000.
  soup.positions[soup.faces[1000][0]].z = std::numeric_limits<double>::quiet_NaN();
  const detail::FrameMap frames[] = {
      {{0.0, 0.0, 0.0}, 1.0}, {{1.5, -2.0, 30.0}, 1.0 / 70.0}, {{-3.0, 0.25, 7.0}, 1e37}};
  const auto faces = static_cast<std::uint32_t>(soup.faces.size());
  const double* positions = &soup.positions[0].x;
  const std::uint32_t* corners = soup.faces[0].data();
  for (const detail::FrameMap& frame : frames)
    for (int round = 0; round < 200; ++round) {
      const auto begin =
          static_cast<std::uint32_t>(round % 4 == 0 ? 970 + round % 23 : rng() % faces);
      const std::uint32_t end = std::min(faces, begin + static_cast<std::uint32_t>(rng() % 64));
      std::vector<detail::FaceBox> slow(end - begin + 1), fast(end - begin + 1);
      std::memset(static_cast<void*>(slow.data()), 0xab, slow.size() * sizeof slow[0]);
      std::memset(static_cast<void*>(fast.data()), 0xab, fast.size() * sizeof fast[0]);
      detail::LaneBounds boxes_a, centres_a, boxes_b, centres_b;
      detail::CornerBounds corners_a, corners_b;
      detail::face_boxes(positions, corners, begin, end, frame, slow.data(), boxes_a, centres_a,
                         corners_a);
      detail::face_boxes_avx2(positions, corners, begin, end, frame, fast.data(), boxes_b,
                              centres_b, corners_b);
      // The corners' own bounds are equal (the lanes may meet -0 and +0 in another order).
      for (int k = 0; k < 3; ++k) {
        ASSERT_EQ(corners_a.lo[k], corners_b.lo[k]) << "faces " << begin << " .. " << end;
        ASSERT_EQ(corners_a.hi[k], corners_b.hi[k]) << "faces " << begin << " .. " << end;
      }
      ASSERT_TRUE(same_bits(slow.data(), fast.data(), slow.size() * sizeof slow[0]))
          << "faces " << begin << " .. " << end;
      ASSERT_TRUE(same_bits(&boxes_a, &boxes_b, sizeof boxes_a))
          << "faces " << begin << " .. " << end;
      ASSERT_TRUE(same_bits(&centres_a, &centres_b, sizeof centres_a))
          << "faces " << begin << " .. " << end;
    }
}

// The baseline against its definition: each record is the tightest float box around the face's
// frame coordinates (lo the largest float not above the least, hi the least float not below the
// largest), with the face index in lane 3 of lo and 0 in lane 3 of hi; the bounds are the boxes'
// and the centres' (lo + hi) minima and maxima; the corner bounds, extended from what they held,
// are the box of the faces' corners; nothing is written past the range.
TEST(FaceBoxes, BaselineMatchesItsDefinition) {
  const TriMesh soup = test::kernel_soup(500, 3);
  const detail::FrameMap frame{{2.0, -1.0, 0.5}, 1.0 / 60.0};
  const std::uint32_t begin = 17, end = 480;
  std::vector<detail::FaceBox> out(end - begin + 1);
  std::memset(static_cast<void*>(out.data()), 0xab, out.size() * sizeof out[0]);
  detail::LaneBounds boxes, centres;
  detail::CornerBounds corner_bounds;
  corner_bounds.hi[1] = 1e9;  // held before: kept
  detail::face_boxes(&soup.positions[0].x, soup.faces[0].data(), begin, end, frame, out.data(),
                     boxes, centres, corner_bounds);
  BoundingBox corner_box;
  for (std::uint32_t f = begin; f < end; ++f)
    for (std::uint32_t v : soup.faces[f]) corner_box.extend(soup.positions[v]);
  ASSERT_LT(corner_box.max[1], 1e9);
  corner_box.max[1] = 1e9;
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(corner_bounds.lo[k], corner_box.min[k]) << k;
    EXPECT_EQ(corner_bounds.hi[k], corner_box.max[k]) << k;
  }
  float box_lo[3], box_hi[3], centre_lo[3], centre_hi[3];
  for (int k = 0; k < 3; ++k) {
    box_lo[k] = centre_lo[k] = std::numeric_limits<float>::infinity();
    box_hi[k] = centre_hi[k] = -std::numeric_limits<float>::infinity();
  }
  for (std::uint32_t f = begin; f < end; ++f) {
    const detail::FaceBox& box = out[f - begin];
    for (int k = 0; k < 3; ++k) {
      double lo = std::numeric_limits<double>::infinity(), hi = -lo;
      for (int corner = 0; corner < 3; ++corner) {
        const double x = (soup.positions[soup.faces[f][corner]][k] - frame.origin[k]) * frame.scale;
        lo = std::min(lo, x);
        hi = std::max(hi, x);
      }
      EXPECT_LE(box.lo[k], lo);
      EXPECT_GT(std::nextafter(box.lo[k], std::numeric_limits<float>::infinity()), lo);
      EXPECT_GE(box.hi[k], hi);
      EXPECT_LT(std::nextafter(box.hi[k], -std::numeric_limits<float>::infinity()), hi);
      box_lo[k] = std::min(box_lo[k], box.lo[k]);
      box_hi[k] = std::max(box_hi[k], box.hi[k]);
      centre_lo[k] = std::min(centre_lo[k], box.lo[k] + box.hi[k]);
      centre_hi[k] = std::max(centre_hi[k], box.lo[k] + box.hi[k]);
    }
    std::uint32_t face;
    std::memcpy(&face, &box.lo[3], sizeof face);
    EXPECT_EQ(face, f);
    EXPECT_EQ(box.hi[3], 0.0f);
  }
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(boxes.lo[k], box_lo[k]);
    EXPECT_EQ(boxes.hi[k], box_hi[k]);
    EXPECT_EQ(centres.lo[k], centre_lo[k]);
    EXPECT_EQ(centres.hi[k], centre_hi[k]);
  }
  std::uint32_t guard;
  std::memcpy(&guard, &out.back().lo[0], sizeof guard);
  EXPECT_EQ(guard, 0xababababu);
}

}  // namespace
}  // namespace meshdev
