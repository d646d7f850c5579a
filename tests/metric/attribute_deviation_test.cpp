#include "metric/attribute_deviation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <string>

#include "metric/errors.h"
#include "metric/memory_limit.h"
#include "tests/support/shapes.h"

namespace meshdev {
namespace {

// Two grids 0.1 apart with normals, per-corner colours and a per-face scalar, so that samples at
// A's vertices have up to six equidistant faces on B with different colours and scalars.
TriMesh with_channels(TriMesh m, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  AttributeChannel& n = m.add_channel("normal", AttributeKind::kNormal, Storage::kPerVertex, 3);
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    n.values[3 * v] = u(rng) - 0.5;
    n.values[3 * v + 1] = u(rng) - 0.5;
    n.values[3 * v + 2] = v % 5 == 0 ? 0.0 : 1.0 + u(rng);  // some zero-length normals
    if (v % 5 == 0) n.values[3 * v] = n.values[3 * v + 1] = 0.0;
  }
  AttributeChannel& c = m.add_channel("color", AttributeKind::kColor, Storage::kPerCorner, 3);
  for (double& x : c.values) x = u(rng);
  AttributeChannel& s = m.add_channel("id", AttributeKind::kScalar, Storage::kPerFace, 1);
  for (double& x : s.values) x = 10 * u(rng);
  return m;
}

// The brute-force twin: every sample's ties from the brute-force index, each measure the minimum
// of attribute_distance over them.
TEST(AttributeDeviation, EqualsThePerTieMinimumOfAttributeDistanceOverTheBruteForceTies) {
  const TriMesh a = with_channels(test::grid(6, 1.0, 0.1), 1);
  const TriMesh b = with_channels(test::grid(6, 1.0, 0.0), 2);
  const AttributePlan plan = plan_attributes(a, b, {}, "A", "B");
  ASSERT_EQ(plan.measures.size(), 7u);  // geometry, normal x2, color x3, id
  SamplingOptions so;
  so.faces = FaceSampling::kMonteCarlo;
  so.target_count = 2000;
  // Several chunks of 1,024, queried chunk by chunk in their face order (spatially coherent), and
  // the same samples shuffled, which are queried in the order of their coarse Morton cells.
  SampleSet face_order = sample_surface(a, so, 1.0);
  ASSERT_GT(face_order.samples.size(), 2048u);
  SampleSet shuffled = face_order;
  std::shuffle(shuffled.samples.begin(), shuffled.samples.end(), std::mt19937_64(3));
  const auto bvh = make_nearest_point_index(b, IndexKind::kBvh);
  const auto brute = make_nearest_point_index(b, IndexKind::kBruteForce);
  // With the default prefetch threshold (this reference is below it) and with the reference's
  // channels prefetched (0): the same results, the prefetching loop run under the sanitizers.
  for (const bool shuffle : {false, true})
    for (const std::size_t prefetch_bytes : {DeviationOptions{}.prefetch_bytes, std::size_t{0}}) {
      SCOPED_TRACE("prefetch_bytes " + std::to_string(prefetch_bytes) +
                   (shuffle ? ", shuffled" : ""));
      const SampleSet& samples = shuffle ? shuffled : face_order;
      DeviationOptions options;
      options.threads = 2;
      options.prefetch_bytes = prefetch_bytes;
      const SampleDeviations d =
          compute_deviations(samples, plan.a, plan.b, *bvh, plan.measures, options);
      EXPECT_EQ(d.cell_order, shuffle);
      // The team (of at most the 2 threads asked for) answered every sample once between them.
      ASSERT_FALSE(d.samples_per_thread.empty());
      EXPECT_LE(d.samples_per_thread.size(), 2u);
      EXPECT_EQ(
          std::accumulate(d.samples_per_thread.begin(), d.samples_per_thread.end(), std::size_t{0}),
          samples.samples.size());

      std::vector<SurfaceHit> ties;
      std::size_t with_ties = 0, tie_changed_value = 0;
      double fa[16], fb[16];
      for (std::size_t i = 0; i < samples.samples.size(); ++i) {
        const Sample& s = samples.samples[i];
        const double distance = brute->find(s.point, sample_hint(a, s), ties);
        ASSERT_EQ(d.values[0][i], distance) << "sample " << i;
        ASSERT_EQ(d.tie_count[i], ties.size()) << "sample " << i;
        ASSERT_EQ(d.nearest_feature[i], ties.front().feature) << "sample " << i;
        with_ties += ties.size() > 1;
        for (std::size_t m = 1; m < plan.measures.size(); ++m) {
          const Measure& measure = plan.measures[m];
          const AttributeChannel& ca = *plan.a.channel(measure.channel);
          const AttributeChannel& cb = *plan.b.channel(measure.channel);
          interpolate(ca, a, s.face, s.bary, s.vertex, fa);
          double best = std::numeric_limits<double>::infinity(), first = 0;
          for (std::size_t t = 0; t < ties.size(); ++t) {
            interpolate(cb, b, ties[t].face, ties[t].bary, kNoFace, fb);
            const double x = attribute_distance(measure.kind, fa, fb, ca.dim);
            if (t == 0) first = x;
            best = std::min(best, x);
          }
          tie_changed_value += best != first;
          ASSERT_EQ(d.values[m][i], best) << measure.name << ", sample " << i;
        }
      }
      EXPECT_GT(with_ties, 10u);          // the tie rule is exercised ...
      EXPECT_GT(tie_changed_value, 10u);  // ... and changes values
    }
}

// Per-vertex channels only (normals with some of zero length, a scalar, UVs), which the
// deviation loop computes inline for samples with one tie: the same numbers, bit for bit, as
// the per-tie minimum of attribute_distance over the brute-force ties (the general path's
// oracle above), on samples with one tie and with several.
TEST(AttributeDeviation, InlinePerVertexChannelsEqualTheBruteForceOracle) {
  // Normals of zero length at every seventh vertex and in a band of x (`zero_band`: whole faces
  // there interpolate to 0, on A's side in one band and on B's in another).
  auto per_vertex = [](TriMesh m, std::uint64_t seed, auto zero_band) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    AttributeChannel& n = m.add_channel("normal", AttributeKind::kNormal, Storage::kPerVertex, 3);
    for (std::size_t v = 0; v < m.positions.size(); ++v) {
      const bool zero = v % 7 == 0 || zero_band(m.positions[v].x);
      n.values[3 * v] = zero ? 0.0 : u(rng) - 0.5;
      n.values[3 * v + 1] = zero ? 0.0 : u(rng) - 0.5;
      n.values[3 * v + 2] = zero ? 0.0 : (v % 3 == 0 ? -1.0 : 1.0) * (0.2 + u(rng));
    }
    AttributeChannel& t =
        m.add_channel("temperature", AttributeKind::kScalar, Storage::kPerVertex, 1);
    for (double& x : t.values) x = 100 * u(rng);
    AttributeChannel& uv =
        m.add_channel("texcoord", AttributeKind::kTexCoord, Storage::kPerVertex, 2);
    for (double& x : uv.values) x = u(rng);
    // Raw values of 3 and 4 components: the unrolled distance and the one of run-time dimension.
    for (int dim : {3, 4}) {
      AttributeChannel& c = m.add_channel("stress" + std::to_string(dim), AttributeKind::kScalar,
                                          Storage::kPerVertex, dim);
      for (double& x : c.values) x = 10 * u(rng) - 5;
    }
    return m;
  };
  const TriMesh a =  // vertices over B's: ties
      per_vertex(test::grid(6, 1.0, 0.1), 5, [](double x) { return x < 0.2; });
  const TriMesh b = per_vertex(test::grid(6, 1.0, 0.0), 6, [](double x) { return x > 0.8; });
  const AttributePlan plan = plan_attributes(a, b, {}, "A", "B");
  // geometry, normal x2, temperature, texcoord, stress3, stress4
  ASSERT_EQ(plan.measures.size(), 7u);
  SamplingOptions so;
  so.faces = FaceSampling::kMonteCarlo;
  so.target_count = 3000;
  const SampleSet samples = sample_surface(a, so, 1.0);  // A's vertices (ties) and faces
  const auto bvh = make_nearest_point_index(b, IndexKind::kBvh);
  const auto brute = make_nearest_point_index(b, IndexKind::kBruteForce);
  // The target's values prefetched (prefetch_bytes 0) or not: the same results either way.
  for (const std::size_t prefetch_bytes : {DeviationOptions{}.prefetch_bytes, std::size_t{0}}) {
    SCOPED_TRACE("prefetch_bytes " + std::to_string(prefetch_bytes));
    DeviationOptions options;
    options.threads = 2;
    options.prefetch_bytes = prefetch_bytes;
    const SampleDeviations d =
        compute_deviations(samples, plan.a, plan.b, *bvh, plan.measures, options);
    std::vector<SurfaceHit> ties;
    std::size_t single = 0, several = 0, angles_beyond_90 = 0, zero_a = 0, zero_b = 0;
    double fa[16], fb[16];
    for (std::size_t i = 0; i < samples.samples.size(); ++i) {
      const Sample& s = samples.samples[i];
      ASSERT_EQ(d.values[0][i], brute->find(s.point, sample_hint(a, s), ties)) << "sample " << i;
      ASSERT_EQ(d.tie_count[i], ties.size()) << "sample " << i;
      (ties.size() == 1 ? single : several) += 1;
      for (std::size_t m = 1; m < plan.measures.size(); ++m) {
        const Measure& measure = plan.measures[m];
        const AttributeChannel& ca = *plan.a.channel(measure.channel);
        const AttributeChannel& cb = *plan.b.channel(measure.channel);
        interpolate(ca, a, s.face, s.bary, s.vertex, fa);
        double best = std::numeric_limits<double>::infinity();
        for (const SurfaceHit& h : ties) {
          interpolate(cb, b, h.face, h.bary, kNoFace, fb);
          best = std::min(best, attribute_distance(measure.kind, fa, fb, ca.dim));
          if (measure.kind == MeasureKind::kNormalAngle && ties.size() == 1) {
            zero_a += fa[0] == 0.0 && fa[1] == 0.0 && fa[2] == 0.0;
            zero_b += fb[0] == 0.0 && fb[1] == 0.0 && fb[2] == 0.0;
          }
        }
        ASSERT_EQ(d.values[m][i], best) << measure.name << ", sample " << i;
        angles_beyond_90 += measure.kind == MeasureKind::kNormalAngle && best > 90.0;
      }
    }
    EXPECT_GT(single, 2000u);           // the inline path (samples 4, 2 or 1 at a time) ...
    EXPECT_GT(several, 10u);            // ... and the general one
    EXPECT_GT(angles_beyond_90, 100u);  // both branches of the angle
    EXPECT_GT(zero_a, 100u);            // zero normals on the inline path, either side
    EXPECT_GT(zero_b, 100u);
  }
}

// Samples made a chunk at a time as they are queried give the results of the stored set, bit for
// bit: Monte Carlo samples (MonteCarloSamples) and the default vertices and scan conversion
// (SampleSequence), on a mesh whose faces are stored along the surface and on the same mesh with
// its faces shuffled. Both sets come along a Morton curve whatever the faces' order, so neither
// is queried in the coarse cell order (which shuffled stored sets get:
// EqualsThePerTieMinimumOfAttributeDistanceOverTheBruteForceTies).
TEST(AttributeDeviation, SamplesMadeAsTheyAreQueriedGiveTheStoredSetsResults) {
  TriMesh shuffled_grid = test::grid(40, 1.0, 0.1);  // 3,200 faces, about 2 samples each
  std::shuffle(shuffled_grid.faces.begin(), shuffled_grid.faces.end(), std::mt19937_64(4));
  const TriMesh b = with_channels(test::grid(6, 1.0, 0.0), 2);
  for (const bool shuffle : {false, true}) {
    SCOPED_TRACE(shuffle ? "faces shuffled" : "faces in grid order");
    const TriMesh a = with_channels(shuffle ? shuffled_grid : test::grid(40, 1.0, 0.1), 1);
    const AttributePlan plan = plan_attributes(a, b, {}, "A", "B");
    const auto bvh = make_nearest_point_index(b, IndexKind::kBvh);
    DeviationOptions options;
    options.threads = 2;
    auto expect_same = [&](const SampleDeviations& x, const SampleDeviations& y) {
      EXPECT_FALSE(x.cell_order);
      EXPECT_FALSE(y.cell_order);
      ASSERT_EQ(x.values.size(), y.values.size());
      for (std::size_t m = 0; m < x.values.size(); ++m)
        EXPECT_TRUE(x.values[m] == y.values[m]) << plan.measures[m].name;
      EXPECT_TRUE(x.tie_count == y.tie_count);
      EXPECT_TRUE(x.nearest_feature == y.nearest_feature);
      for (const SampleDeviations* d : {&x, &y})
        EXPECT_EQ(std::accumulate(d->samples_per_thread.begin(), d->samples_per_thread.end(),
                                  std::size_t{0}),
                  d->values[0].size());
      ASSERT_EQ(x.nearest.size(), y.nearest.size());
      for (std::size_t i = 0; i < x.nearest.size(); ++i) {
        ASSERT_EQ(x.nearest[i].face, y.nearest[i].face) << "sample " << i;
        ASSERT_EQ(x.nearest[i].point, y.nearest[i].point) << "sample " << i;
      }
    };
    SamplingOptions so;
    so.vertices = false;
    so.faces = FaceSampling::kMonteCarlo;
    so.target_count = 6000;
    so.threads = 2;
    const SampleSet stored = sample_surface(a, so, 1.0);
    ASSERT_GT(stored.samples.size(), 4 * 1024u);
    expect_same(compute_deviations(stored, plan.a, plan.b, *bvh, plan.measures, options),
                compute_deviations(monte_carlo_samples(a, so), plan.a, plan.b, *bvh, plan.measures,
                                   options));
    SamplingOptions scan;  // the default kinds: vertices and scan conversion
    scan.target_count = 6000;
    scan.threads = 2;
    const SampleSet stored_scan = sample_surface(a, scan, 1.0);
    ASSERT_GT(stored_scan.samples.size(), 4 * 1024u);
    expect_same(compute_deviations(stored_scan, plan.a, plan.b, *bvh, plan.measures, options),
                compute_deviations(SampleSequence(a, scan, 1.0), plan.a, plan.b, *bvh,
                                   plan.measures, options));
  }
}

// Deviations that cannot fit in this machine's memory are refused before anything is allocated
// or queried, saying what they need: 2^31 Monte Carlo samples, made on demand (no sample set),
// with the nearest points kept: about 100 bytes each.
TEST(AttributeDeviation, DeviationsBeyondTheMemoryAreRefusedBeforeAnyQuery) {
  const TriMesh a = with_channels(test::grid(4, 1.0, 0.1), 1);
  const TriMesh b = with_channels(test::grid(4, 1.0, 0.0), 2);
  const AttributePlan plan = plan_attributes(a, b, {}, "A", "B");
  const double needed = std::ldexp(1.0, 31) * deviation_bytes_per_sample(plan.measures, {});
  EXPECT_EQ(deviation_bytes_per_sample(plan.measures, {}),
            static_cast<double>(plan.measures.size() * sizeof(double)) + 5.0 + sizeof(SurfaceHit));
  if (fits_in_memory(needed))
    GTEST_SKIP() << "this machine has room for the deviations of 2^31 samples";
  SamplingOptions so;
  so.vertices = false;
  so.faces = FaceSampling::kMonteCarlo;
  so.target_count = std::size_t{1} << 31;
  const MonteCarloSamples samples = monte_carlo_samples(a, so);
  const auto bvh = make_nearest_point_index(b, IndexKind::kBvh);
  try {
    compute_deviations(samples, plan.a, plan.b, *bvh, plan.measures, DeviationOptions{});
    FAIL() << "no exception";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("the deviations of 2147483648 samples need about"),
              std::string::npos)
        << e.what();
  }
}

// Measures sharing a transform (unit normals, CIELAB) compute it once; the result is the same,
// bit for bit, as transforming inside attribute_distance.
TEST(AttributeDeviation, FormDistanceOfTransformedValuesIsAttributeDistance) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-0.2, 1.2);
  for (MeasureKind kind :
       {MeasureKind::kNormalEuclidean, MeasureKind::kNormalAngle, MeasureKind::kColorRgb,
        MeasureKind::kColorDeltaE76, MeasureKind::kColorDeltaE2000,
        MeasureKind::kTextureColorDeltaE2000, MeasureKind::kScalar}) {
    for (int trial = 0; trial < 200; ++trial) {
      double x[3] = {u(rng), u(rng), u(rng)}, y[3] = {u(rng), u(rng), u(rng)};
      if (trial == 0) x[0] = x[1] = x[2] = 0.0;
      double fx[3], fy[3];
      to_form(value_form(kind), x, 3, fx);
      to_form(value_form(kind), y, 3, fy);
      ASSERT_EQ(form_distance(kind, fx, fy, 3), attribute_distance(kind, x, y, 3));
    }
  }
  EXPECT_EQ(value_form(MeasureKind::kNormalAngle), ValueForm::kUnit);
  EXPECT_EQ(value_form(MeasureKind::kColorDeltaE76), ValueForm::kLab);
  EXPECT_EQ(value_form(MeasureKind::kColorRgb), ValueForm::kRaw);
}

}  // namespace
}  // namespace meshdev
