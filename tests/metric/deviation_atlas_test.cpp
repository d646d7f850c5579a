// The deviation texture atlas: every sample's texel maps back to the right face and point.
#include "metric/deviation_atlas.h"

#include <gtest/gtest.h>

#include <cmath>

#include "metric/compare.h"
#include "metric/errors.h"
#include "tests/support/shapes.h"

namespace meshdev {
namespace {

constexpr double kSlope = 0.1;

// A = [0,1]^2 at z = 0; B = the plane z = 0.1 x over [-1,2]^2. The deviation of A at (x, y, 0) is
// the distance to that plane, 0.1 |x| / sqrt(1.01): a known field that varies inside faces.
double known_field(const Vec3& p) {
  return kSlope * std::fabs(p.x) / std::sqrt(1 + kSlope * kSlope);
}

ComparisonResult tilted_plane_comparison(const TriMesh& a, FaceSampling faces) {
  TriMesh b = test::translated(test::grid(3, 3.0), {-1, -1, 0});
  for (Vec3& p : b.positions) p.z = kSlope * p.x;
  CompareOptions o;
  o.attributes.attributes = {"geometry"};
  o.sampling.step = 0.04;
  o.sampling.faces = faces;
  o.sampling.target_count = 2000;
  o.direction = Direction::kForward;
  o.keep_samples = true;
  return compare_meshes(a, b, o);
}

// Barycentrics of UV point (u, v) in face f's atlas UV triangle.
std::array<double, 3> atlas_bary(const TriMesh& m, std::size_t f, double u, double v) {
  const AttributeChannel& uv = *m.channel("texcoord");
  const double* p0 = uv.element(3 * f);
  const double* p1 = uv.element(3 * f + 1);
  const double* p2 = uv.element(3 * f + 2);
  const double det = (p1[0] - p0[0]) * (p2[1] - p0[1]) - (p2[0] - p0[0]) * (p1[1] - p0[1]);
  const double s = ((u - p0[0]) * (p2[1] - p0[1]) - (p2[0] - p0[0]) * (v - p0[1])) / det;
  const double t = ((p1[0] - p0[0]) * (v - p0[1]) - (u - p0[0]) * (p1[1] - p0[1])) / det;
  return {1 - s - t, s, t};
}

TEST(DeviationAtlas, SampleTexelsMapBackToTheirFaceAndPoint) {
  const TriMesh a = test::grid(3);
  const ComparisonResult r = tilted_plane_comparison(a, FaceSampling::kScanConversion);
  const DeviationAtlas atlas = build_deviation_atlas(a, *r.forward, AtlasOptions{});
  ASSERT_GT(atlas.size, 0);
  EXPECT_EQ(atlas.sample_texels, r.forward->sample_set.face_count);
  EXPECT_GT(atlas.sample_efficiency, 0.2);
  EXPECT_LE(atlas.sample_efficiency, atlas.rectangle_efficiency);
  EXPECT_LE(atlas.rectangle_efficiency, 1.0);

  std::vector<std::size_t> per_face(a.num_faces(), 0);
  for (int y = 0; y < atlas.size; ++y)
    for (int x = 0; x < atlas.size; ++x) {
      const std::size_t t = static_cast<std::size_t>(y) * atlas.size + x;
      if (!atlas.texel_is_sample[t]) continue;
      const std::int32_t f = atlas.texel_face[t];
      ASSERT_GE(f, 0);
      ++per_face[static_cast<std::size_t>(f)];
      // The texel centre, through face f's atlas UVs, is a point of face f ...
      const double u = (x + 0.5) / atlas.size, v = 1.0 - (y + 0.5) / atlas.size;
      const std::array<double, 3> w = atlas_bary(atlas.mesh, static_cast<std::size_t>(f), u, v);
      for (double c : w) EXPECT_GE(c, -1e-9) << "texel outside its face's UV triangle";
      const Triangle& tri = a.faces[static_cast<std::size_t>(f)];
      const Vec3 p =
          w[0] * a.positions[tri[0]] + w[1] * a.positions[tri[1]] + w[2] * a.positions[tri[2]];
      // ... whose deviation is the texel's value, and whose colour is the texel's colour.
      EXPECT_NEAR(atlas.texel_value[t], known_field(p), 1e-6);
      const Vec3 expected = map_color(atlas.texel_value[t], atlas.lo, atlas.hi);
      const Vec3 looked_up = sample_bilinear(atlas.image, u, v);
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(looked_up[k], expected[k], 0.5 / 255 + 1e-9);
    }
  // Every face sample has its texel in its own face's rectangle.
  std::vector<std::size_t> samples_of(a.num_faces(), 0);
  for (const Sample& s : r.forward->sample_set.samples)
    if (s.kind == SampleKind::kFace) ++samples_of[s.face];
  EXPECT_EQ(per_face, samples_of);
}

TEST(DeviationAtlas, FilteringAnywhereInsideAFaceStaysWithinItsSamples) {
  // Bilinear lookups at random points of each face only mix texels of that face: the value range
  // seen inside the face is within the face's own sample range.
  const TriMesh a = test::grid(2);
  const ComparisonResult r = tilted_plane_comparison(a, FaceSampling::kScanConversion);
  const DeviationAtlas atlas = build_deviation_atlas(a, *r.forward, AtlasOptions{});
  const AttributeChannel& uv = *atlas.mesh.channel("texcoord");
  for (std::size_t f = 0; f < a.num_faces(); ++f)
    for (double s = 0.05; s < 1.0; s += 0.15)
      for (double t = 0.05; s + t < 1.0; t += 0.15) {
        const double u = (1 - s - t) * uv.element(3 * f)[0] + s * uv.element(3 * f + 1)[0] +
                         t * uv.element(3 * f + 2)[0];
        const double v = (1 - s - t) * uv.element(3 * f)[1] + s * uv.element(3 * f + 1)[1] +
                         t * uv.element(3 * f + 2)[1];
        const int x = static_cast<int>(std::floor(u * atlas.size - 0.5));
        const int y = static_cast<int>(std::floor((1 - v) * atlas.size - 0.5));
        for (int dy = 0; dy <= 1; ++dy)
          for (int dx = 0; dx <= 1; ++dx)
            EXPECT_EQ(atlas.texel_face[static_cast<std::size_t>(y + dy) * atlas.size + x + dx],
                      static_cast<std::int32_t>(f));
      }
}

TEST(DeviationAtlas, RefusesMonteCarloSamplesAndMissingSamples) {
  const TriMesh a = test::grid(2);
  const ComparisonResult mc = tilted_plane_comparison(a, FaceSampling::kMonteCarlo);
  EXPECT_THROW(build_deviation_atlas(a, *mc.forward, AtlasOptions{}), InvalidInput);
  DirectionResult empty;
  EXPECT_THROW(build_deviation_atlas(a, empty, AtlasOptions{}), InvalidInput);
}

}  // namespace
}  // namespace meshdev
