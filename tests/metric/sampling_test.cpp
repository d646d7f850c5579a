#include "metric/sampling.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "metric/errors.h"
#include "metric/io/mesh_io.h"
#include "metric/memory_limit.h"
#include "metric/morton_order.h"
#include "tests/support/shapes.h"
#include "tests/support/test_data.h"

namespace meshdev {
namespace {

// Sample i made on demand (x) is the stored one (y), field by field, bit for bit.
void expect_same_sample(const Sample& x, const Sample& y, std::size_t i) {
  ASSERT_EQ(x.point, y.point) << "sample " << i;
  ASSERT_EQ(x.face, y.face) << "sample " << i;
  ASSERT_EQ(x.vertex, y.vertex) << "sample " << i;
  ASSERT_EQ(x.bary, y.bary) << "sample " << i;
  ASSERT_EQ(x.weight, y.weight) << "sample " << i;
  ASSERT_EQ(x.kind, y.kind) << "sample " << i;
}

// Monte Carlo face samples alone, `count` of them.
SamplingOptions monte_carlo_options(std::size_t count) {
  SamplingOptions o;
  o.vertices = false;
  o.faces = FaceSampling::kMonteCarlo;
  o.target_count = count;
  return o;
}

// Eq. 5-6 on the right triangle with legs 1: points (iΔ, jΔ) with i + j <= 1/Δ.
TEST(Sampling, ScanConversionCountFollowsEquationSix) {
  const Vec3 a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0};
  EXPECT_EQ(scan_conversion_count(a, b, c, 0.25), 15u);  // 5 + 4 + 3 + 2 + 1
  EXPECT_EQ(scan_conversion_count(a, b, c, 0.1), 66u);   // 11 + 10 + ... + 1
  EXPECT_EQ(scan_conversion_count(a, b, c, 5.0), 1u);    // a face smaller than Δ keeps corner A
}

TEST(Sampling, FaceSamplesLieOnTheirFaceWithValidBarycentrics) {
  TriMesh m = test::icosphere(1);
  SamplingOptions o;
  o.step = 0.05;
  SampleSet set = sample_surface(m, o, 1.0);
  ASSERT_GT(set.face_count, 0u);
  for (const Sample& s : set.samples) {
    ASSERT_NE(s.face, kNoFace);
    const Triangle& t = m.faces[s.face];
    EXPECT_NEAR(s.bary[0] + s.bary[1] + s.bary[2], 1.0, 1e-12);
    for (double b : s.bary) EXPECT_GE(b, -1e-12);
    const Vec3 q = s.bary[0] * m.positions[t[0]] + s.bary[1] * m.positions[t[1]] +
                   s.bary[2] * m.positions[t[2]];
    EXPECT_NEAR(norm(q - s.point), 0.0, 1e-12);
  }
}

// The face samplers place each sample in raw storage (SampleAllocator): every field must be
// written, in the layout vertices, then edges, then faces. Both face samplers, edges included.
TEST(Sampling, EverySampleIsCompleteAndTheKindsComeInOrder) {
  TriMesh m = test::icosphere(2);
  for (FaceSampling faces : {FaceSampling::kScanConversion, FaceSampling::kMonteCarlo}) {
    SamplingOptions o;
    o.edges = true;
    o.faces = faces;
    o.step_fraction = 0.05;
    o.target_count = 3000;
    const SampleSet set = sample_surface(m, o, 2.0);
    ASSERT_EQ(set.vertex_count + set.edge_count + set.face_count, set.samples.size());
    ASSERT_GT(set.face_count, 0u);
    for (std::size_t i = 0; i < set.samples.size(); ++i) {
      const Sample& s = set.samples[i];
      const SampleKind want = i < set.vertex_count                    ? SampleKind::kVertex
                              : i < set.vertex_count + set.edge_count ? SampleKind::kEdge
                                                                      : SampleKind::kFace;
      ASSERT_EQ(s.kind, want) << "sample " << i;
      ASSERT_LT(s.face, m.num_faces()) << "sample " << i;
      if (want == SampleKind::kVertex) {
        ASSERT_LT(s.vertex, m.num_vertices()) << "sample " << i;
        EXPECT_EQ(s.point, m.positions[s.vertex]);
      } else {
        ASSERT_EQ(s.vertex, kNoFace) << "sample " << i;
      }
      if (want == SampleKind::kFace)
        ASSERT_GT(s.weight, 0.0) << "sample " << i;
      else
        ASSERT_EQ(s.weight, 0.0) << "sample " << i;  // face samples present: hunt the maximum
      ASSERT_NEAR(s.bary[0] + s.bary[1] + s.bary[2], 1.0, 1e-12) << "sample " << i;
    }
  }
}

TEST(Sampling, FaceWeightsSumToTheAreaAndVertexSamplesOnlyHuntTheMaximum) {
  TriMesh m = test::icosphere(2);
  SamplingOptions o;
  o.step_fraction = 0.02;
  SampleSet set = sample_surface(m, o, 2.0);
  double faces = 0.0, others = 0.0;
  for (const Sample& s : set.samples) (s.kind == SampleKind::kFace ? faces : others) += s.weight;
  EXPECT_NEAR(faces, surface_area(m), 1e-9);
  EXPECT_EQ(others, 0.0);
  EXPECT_EQ(set.vertex_count, m.num_vertices());
  EXPECT_NEAR(set.step, 0.04, 1e-15);
}

TEST(Sampling, TargetCountIsMetWithinOnePercent) {
  TriMesh m = test::icosphere(3);
  SamplingOptions o;
  o.vertices = false;
  o.target_count = 50000;
  SampleSet set = sample_surface(m, o, 2.0);
  EXPECT_NEAR(static_cast<double>(set.face_count), 50000.0, 500.0);
}

// A face's scan-conversion count never grows with Δ (detail::solve_scan_step relies on it), in
// floating point too: every operation of the count is correctly rounded and monotone in Δ.
// Random triangles, steps swept finely across each one's row and column boundaries.
TEST(Sampling, ScanConversionCountNeverGrowsWithTheStep) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int k = 0; k < 200; ++k) {
    const Vec3 a{u(rng), u(rng), u(rng)}, b{u(rng), u(rng), u(rng)}, c{u(rng), u(rng), u(rng)};
    std::size_t before = std::numeric_limits<std::size_t>::max();
    for (double step = 0.02; step < 2.0; step *= 1.0 + 1e-3) {
      const std::size_t n = scan_conversion_count(a, b, c, step);
      ASSERT_LE(n, before) << "triangle " << k << ", step " << step;
      before = n;
    }
  }
}

// Settling faces whose count no longer changes gives the Δ of counting every face at every
// step, bit for bit, on any team: on meshes of even faces, random soups with slivers and
// degenerate faces, and targets from a few samples per face to thousands.
TEST(Sampling, SolvedStepIsTheSameWithSettledFacesSkipped) {
  const TriMesh meshes[] = {test::icosphere(3), test::grid(30), test::random_soup(3000, 7, 0.2),
                            test::random_soup(500, 8, 0.0)};
  for (const TriMesh& m : meshes)
    for (const std::size_t per_face : {1, 3, 10, 100, 2000}) {
      const std::size_t target = per_face * m.num_faces();
      const double plain = detail::solve_scan_step(m, target, 1, false);
      for (int threads : {1, 2, 3}) {
        const double settled = detail::solve_scan_step(m, target, threads, true);
        EXPECT_EQ(settled, plain) << m.num_faces() << " faces, target " << target << ", " << threads
                                  << " threads";
      }
    }
}

// The same on a real scan (libcgal-demo's bunny, 144k faces with Debian's package).
TEST(Sampling, SolvedStepIsTheSameWithSettledFacesSkippedOnARealScan) {
  const std::string path = test::cgal_mesh("bunny00.off");
  if (path.empty()) GTEST_SKIP() << "libcgal-demo is not installed (no CGAL data archive)";
  const TriMesh m = read_mesh(path);
  for (const std::size_t per_face : {2, 10})
    EXPECT_EQ(detail::solve_scan_step(m, per_face * m.num_faces(), 2, true),
              detail::solve_scan_step(m, per_face * m.num_faces(), 1, false));
}

TEST(Sampling, MonteCarloDependsOnlyOnTheSeed) {
  TriMesh m = test::icosphere(2);
  SamplingOptions o = monte_carlo_options(20000);
  o.seed = 7;
  SampleSet x = sample_surface(m, o, 2.0), y = sample_surface(m, o, 2.0);
  ASSERT_EQ(x.samples.size(), y.samples.size());
  for (std::size_t i = 0; i < x.samples.size(); ++i)
    ASSERT_EQ(x.samples[i].point, y.samples[i].point);
  EXPECT_NEAR(static_cast<double>(x.face_count), 20000.0, 600.0);
  o.seed = 8;
  SampleSet z = sample_surface(m, o, 2.0);
  EXPECT_NE(z.samples[0].point, x.samples[0].point);
}

// MonteCarloSamples makes, for any range, exactly the samples sample_surface stores for Monte
// Carlo faces alone (which it makes through that class): a soup with degenerate (zero-area)
// faces that get no samples, ranges that start and end inside faces and cross empty ones.
TEST(Sampling, MonteCarloSamplesMakeTheStoredSetInAnyRange) {
  const TriMesh m = test::random_soup(400, 5, 0.2);
  SamplingOptions o = monte_carlo_options(6000);
  o.seed = 3;
  o.threads = 2;
  ASSERT_TRUE(monte_carlo_only(o));
  const SampleSet set = sample_surface(m, o, 1.0);
  const MonteCarloSamples mc = monte_carlo_samples(m, o);
  ASSERT_EQ(mc.size(), set.samples.size());
  EXPECT_EQ(mc.weight(), set.equal_weight);
  EXPECT_EQ(mc.description(), set.description);
  for (std::size_t i = 0; i < set.samples.size(); ++i)
    expect_same_sample(mc.at(i), set.samples[i], i);
  std::mt19937_64 rng(9);
  std::vector<Sample> out;
  for (int trial = 0; trial < 200; ++trial) {
    const std::size_t begin = rng() % mc.size();
    const std::size_t count = rng() % std::min<std::size_t>(mc.size() - begin, 300);
    out.assign(count + 1, Sample{});
    mc.generate(begin, count, out.data());
    for (std::size_t j = 0; j < count; ++j)
      expect_same_sample(out[j], set.samples[begin + j], begin + j);
    ASSERT_EQ(out[count].face, kNoFace);  // nothing written past the range
  }
  // Options with vertices or edges are not Monte Carlo alone.
  o.vertices = true;
  EXPECT_FALSE(monte_carlo_only(o));
  o.vertices = false;
  o.edges = true;
  EXPECT_FALSE(monte_carlo_only(o));
}

// SampleSequence makes, for any range and on any team, exactly the samples, weights and order
// sample_surface stores, for every sampling without edges: vertices, scan conversion (solved for a
// count, or with a step given) and Monte Carlo, alone and together; on a soup with degenerate
// faces (a zero-area face still gets its corner; Monte Carlo gives it none), a sphere and a
// point cloud. Ranges start and end inside faces, inside rows and across the vertex part's end.
TEST(Sampling, SampleSequenceMakesTheStoredSetInAnyRange) {
  TriMesh cloud;
  cloud.positions = {{0, 0, 0}, {1, 2, 3}, {-1, 0.5, 2}};
  const TriMesh meshes[] = {test::random_soup(400, 5, 0.2), test::icosphere(2), cloud};
  std::mt19937_64 rng(11);
  int checked = 0;
  for (const TriMesh& m : meshes)
    for (const bool vertices : {true, false})
      for (const FaceSampling faces :
           {FaceSampling::kNone, FaceSampling::kScanConversion, FaceSampling::kMonteCarlo})
        for (const double step : {0.0, 0.05}) {
          if (!vertices && faces == FaceSampling::kNone) continue;
          if (m.faces.empty() && faces != FaceSampling::kNone) continue;
          SamplingOptions o;
          o.vertices = vertices;
          o.faces = faces;
          o.step = step;
          o.target_count = 5000;
          o.seed = 3;
          o.threads = 2;
          SCOPED_TRACE(std::to_string(m.num_faces()) + " faces, vertices " +
                       std::to_string(vertices) + ", faces " +
                       std::to_string(static_cast<int>(faces)) + ", step " + std::to_string(step));
          ASSERT_TRUE(sequence_sampling(o));
          const SampleSet set = sample_surface(m, o, 1.0);
          const SampleSequence seq(m, o, 1.0);
          ASSERT_EQ(seq.size(), set.samples.size());
          ASSERT_GT(seq.size(), 0u);
          EXPECT_EQ(seq.vertex_count(), set.vertex_count);
          EXPECT_EQ(seq.face_count(), set.face_count);
          EXPECT_EQ(seq.step(), set.step);
          EXPECT_EQ(seq.equal_weight(), set.equal_weight);
          EXPECT_EQ(seq.description(), set.description);
          for (std::size_t i = 0; i < set.samples.size(); ++i)
            expect_same_sample(seq.at(i), set.samples[i], i);
          std::vector<Sample> out;
          for (int trial = 0; trial < 100; ++trial) {
            const std::size_t begin = rng() % seq.size();
            const std::size_t count = rng() % std::min<std::size_t>(seq.size() - begin, 300);
            out.assign(count + 1, Sample{});
            seq.generate(begin, count, out.data());
            for (std::size_t j = 0; j < count; ++j)
              expect_same_sample(out[j], set.samples[begin + j], begin + j);
            ASSERT_EQ(out[count].face, kNoFace);  // nothing written past the range
          }
          for (int threads : {1, 3}) {
            std::vector<Sample> all(seq.size());
            seq.generate_all(all.data(), threads);
            for (std::size_t i = 0; i < all.size(); ++i)
              expect_same_sample(all[i], set.samples[i], i);
            std::vector<double> weights(seq.size(), -1.0);
            seq.weights(weights.data(), threads);
            for (std::size_t i = 0; i < weights.size(); ++i)
              ASSERT_EQ(weights[i], set.samples[i].weight) << "sample " << i;
          }
          ++checked;
        }
  EXPECT_EQ(checked, 2 * (5 + 5) + 2);  // every combination above was compared
  SamplingOptions o;
  o.edges = true;
  EXPECT_FALSE(sequence_sampling(o));
}

// SampleSequence refuses what sample_surface refuses, with the same errors.
TEST(Sampling, SampleSequenceRefusesWhatTheStoredSamplingRefuses) {
  const TriMesh m = test::grid(40);
  SamplingOptions o;
  o.step = 1e-9;  // more than 2^31 samples
  EXPECT_THROW(SampleSequence(m, o, 1.0), InvalidInput);
  TriMesh cloud;
  cloud.positions = {{0, 0, 0}};
  o.step = 0.1;
  EXPECT_THROW(SampleSequence(cloud, o, 1.0), InvalidInput);  // faces of a point cloud
  o.step = 0;
  o.step_fraction = 0.01;
  TriMesh point = test::square();
  for (Vec3& p : point.positions) p = {1, 1, 1};
  EXPECT_THROW(SampleSequence(point, o, 0.0), InvalidInput);  // a step of 0
}

// A mesh of zero area has no Monte Carlo samples, stored or made.
TEST(Sampling, MonteCarloSamplesOfAZeroAreaMeshAreNone) {
  TriMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  m.faces = {{0, 1, 2}};
  SamplingOptions o = monte_carlo_options(100);
  EXPECT_EQ(monte_carlo_samples(m, o).size(), 0u);
  EXPECT_TRUE(sample_surface(m, o, 1.0).samples.empty());
}

// The set's equal_weight is every sample's weight where the sampling gives them one weight
// (Monte Carlo faces alone, vertices alone), and 0 (read each sample's) where it does not.
TEST(Sampling, EqualWeightIsSetOnlyWhereEverySampleWeighsTheSame) {
  TriMesh m = test::icosphere(2);
  auto sample = [&](bool vertices, FaceSampling faces) {
    SamplingOptions o;
    o.vertices = vertices;
    o.faces = faces;
    o.target_count = 5000;
    return sample_surface(m, o, 2.0);
  };
  for (const SampleSet& set :
       {sample(false, FaceSampling::kMonteCarlo), sample(true, FaceSampling::kNone)}) {
    ASSERT_FALSE(set.samples.empty());
    EXPECT_GT(set.equal_weight, 0.0);
    for (const Sample& s : set.samples) ASSERT_EQ(s.weight, set.equal_weight);
  }
  EXPECT_EQ(sample(true, FaceSampling::kMonteCarlo).equal_weight, 0.0);
  EXPECT_EQ(sample(false, FaceSampling::kScanConversion).equal_weight, 0.0);
}

// Faces are sampled in parallel, each into its own slots: the set is the one a serial pass makes
// (face by face, in face order) for any thread count.
TEST(Sampling, FaceSamplesAreTheSameForAnyThreadCount) {
  const TriMesh m = test::random_soup(300, 11, 0.1);
  for (FaceSampling kind : {FaceSampling::kScanConversion, FaceSampling::kMonteCarlo}) {
    SamplingOptions o;
    o.faces = kind;
    o.target_count = 30000;
    o.threads = 1;
    const SampleSet one = sample_surface(m, o, 1.0);
    std::size_t scan_total = 0;
    for (const Triangle& t : m.faces)
      scan_total +=
          scan_conversion_count(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]], one.step);
    if (kind == FaceSampling::kScanConversion) {
      EXPECT_EQ(one.face_count, scan_total);
    }
    // Each face's samples together, the faces in their visit order.
    const std::vector<std::uint32_t> order = detail::face_visit_order(m, 1);
    std::size_t slot = 0;
    for (std::size_t i = one.vertex_count; i < one.samples.size(); ++i) {
      if (i > one.vertex_count && one.samples[i].face == one.samples[i - 1].face) continue;
      while (slot < order.size() && order[slot] != one.samples[i].face) ++slot;
      ASSERT_LT(slot++, order.size()) << "sample " << i << " on face " << one.samples[i].face;
    }
    for (int threads : {2, 3, 7}) {
      o.threads = threads;
      const SampleSet other = sample_surface(m, o, 1.0);
      ASSERT_EQ(other.samples.size(), one.samples.size());
      for (std::size_t i = 0; i < one.samples.size(); ++i) {
        const Sample &x = one.samples[i], &y = other.samples[i];
        ASSERT_EQ(x.point, y.point) << "sample " << i << ", " << threads << " threads";
        ASSERT_EQ(x.face, y.face);
        ASSERT_EQ(x.bary, y.bary);
        ASSERT_EQ(x.weight, y.weight);
        ASSERT_EQ(x.kind, y.kind);
      }
    }
  }
}

// The visit orders against their definition computed plainly: the points' Morton codes on the
// grid over the box of the mesh's vertices, cut to the 24 bits from the highest in which the
// least and the greatest code differ, sorted stably (points of one cell in index order).
std::vector<std::uint32_t> plain_curve_order(const TriMesh& m, const std::vector<Vec3>& points) {
  const MortonGrid grid(bounding_box(m));  // every vertex is referenced in these meshes
  std::vector<std::uint64_t> code(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) code[i] = grid.code(points[i]);
  const auto [least, most] = std::minmax_element(code.begin(), code.end());
  const int top = *least == *most ? 0 : 63 - __builtin_clzll(*least ^ *most);
  const int low = std::max(0, top - (kMortonSortBits - 1));
  std::vector<std::uint32_t> order(points.size());
  for (std::uint32_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t x, std::uint32_t y) {
    return code[x] >> low < code[y] >> low;
  });
  return order;
}

// The last mesh, 262,088 faces and 131,769 vertices stored shuffled, is large enough for the
// sort's team of 3 threads (16,384 points make a team of 2; under TSan in scripts/sanitize.sh).
TEST(Sampling, FacesAndVerticesAreVisitedAlongAMortonCurve) {
  for (const TriMesh& m : {test::icosphere(3), test::random_soup(2000, 5, 0.1), test::grid(40),
                           test::shuffled(test::grid(362), 7)}) {
    std::vector<Vec3> centre;
    for (const Triangle& t : m.faces)
      centre.push_back((m.positions[t[0]] + m.positions[t[1]] + m.positions[t[2]]) * (1.0 / 3.0));
    for (int threads : {1, 2, 3}) {
      EXPECT_EQ(detail::face_visit_order(m, threads), plain_curve_order(m, centre));
      EXPECT_EQ(detail::vertex_visit_order(m, threads), plain_curve_order(m, m.positions));
    }
  }
}

// The samples' order follows the surface, not the file: a grid with its faces and vertices
// shuffled gives the same samples (as a set) as the grid stored row by row, and consecutive
// samples about as near each other (in index order they would jump across the grid).
TEST(Sampling, SampleOrderFollowsTheSurfaceNotTheFile) {
  const int n = 48;
  const TriMesh plain = test::grid(n);
  const TriMesh shuffled = test::shuffled(plain, 3);

  for (FaceSampling kind : {FaceSampling::kScanConversion, FaceSampling::kMonteCarlo}) {
    SamplingOptions o;
    o.faces = kind;
    o.target_count = 20 * plain.faces.size();
    const SampleSet x = sample_surface(plain, o, std::sqrt(2.0));
    const SampleSet y = sample_surface(shuffled, o, std::sqrt(2.0));
    ASSERT_EQ(x.samples.size(), y.samples.size());
    // Mean step between consecutive samples of one kind, in grid cells.
    auto mean_step = [&](const SampleSet& set, std::size_t begin, std::size_t end) {
      double sum = 0.0;
      for (std::size_t i = begin + 1; i < end; ++i)
        sum += norm(set.samples[i].point - set.samples[i - 1].point);
      return sum / static_cast<double>(end - begin - 1) * n;
    };
    const std::size_t nv = x.vertex_count, total = x.samples.size();
    EXPECT_LT(mean_step(y, 0, nv), 3.0);  // 1.7 here; in index order of the shuffle 26
    EXPECT_LT(mean_step(y, nv, total), 1.5 * mean_step(x, nv, total));
    EXPECT_LT(mean_step(y, nv, total), 0.75);  // 0.4-0.5 here; in index order 1.5-1.7
    // The same points (not for Monte Carlo, whose random numbers hash the face's index).
    if (kind == FaceSampling::kScanConversion) {
      auto points = [](const SampleSet& set) {
        std::vector<std::array<double, 4>> p;
        for (const Sample& s : set.samples)
          p.push_back({s.point.x, s.point.y, s.point.z, s.weight});
        std::sort(p.begin(), p.end());
        return p;
      };
      EXPECT_EQ(points(x), points(y));
    }
  }
}

// A step that would make more than 2^31 samples is refused once the count passes the limit, not
// after counting every face (here ~2.5e7 scan rows per face: counting all 3,200 faces would take
// minutes, so a regression shows as a test timeout).
TEST(Sampling, AStepFarTooSmallIsRefusedAsSoonAsTheCountPassesTheLimit) {
  const TriMesh m = test::grid(40);
  SamplingOptions o;
  o.faces = FaceSampling::kScanConversion;
  o.step = 1e-9;
  for (int threads : {1, 2}) {
    o.threads = threads;
    EXPECT_THROW(sample_surface(m, o, 1.0), InvalidInput);
  }
}

// Edge samples that would be more than 2^31 are refused before any is made: a step far too small
// for the mesh, an edge 1e100 long at a unit step (before, its count was an llround of 1e100,
// undefined, and samples were made until memory ran out), and an edge whose length overflows to
// inf.
TEST(Sampling, EdgeSamplesBeyondTheLimitAreRefusedBeforeAnyIsMade) {
  auto with_edge = [](double from, double to) {  // an edge from (from, 0, 1) to (to, 0, 1)
    TriMesh m = test::grid(4);
    const auto base = static_cast<std::uint32_t>(m.positions.size());
    m.positions.push_back({from, 0, 1});
    m.positions.push_back({to, 0, 1});
    m.positions.push_back({from, 1, 1});
    m.faces.push_back({base, base + 1, base + 2});
    return m;
  };
  SamplingOptions o;
  o.vertices = false;
  o.edges = true;
  o.faces = FaceSampling::kNone;
  o.step = 1e-12;
  EXPECT_THROW(sample_surface(test::grid(4), o, 1.0), InvalidInput);
  o.step = 1.0;
  for (const double from : {0.0, -1e308}) {  // 1e100 long; 2e308, inf
    const TriMesh m = with_edge(from, from == 0.0 ? 1e100 : 1e308);
    try {
      sample_surface(m, o, 1.0);
      ADD_FAILURE() << "edge from " << from << ": no exception";
    } catch (const InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find("more than 2^31 samples"), std::string::npos)
          << e.what();
    }
  }
  const SampleSet fine = sample_surface(with_edge(0.0, 10.0), o, 1.0);  // a count within the limit
  EXPECT_GT(fine.edge_count, 10u);
}

// A target of more than 2^31 face samples is refused with that reason, stored or made on demand,
// by Monte Carlo or scan conversion (before, Monte Carlo allocated them: std::bad_alloc, or the
// OOM killer where the allocation fit the overcommit; scan conversion blamed needles).
TEST(Sampling, ATargetBeyondTheLimitIsRefusedWithThatReason) {
  const TriMesh m = test::grid(4);
  for (const FaceSampling faces : {FaceSampling::kMonteCarlo, FaceSampling::kScanConversion}) {
    SamplingOptions o;
    o.faces = faces;
    o.target_count = (std::size_t{1} << 31) + 1;
    for (const bool vertices : {false, true}) {
      o.vertices = vertices;
      try {
        sample_surface(m, o, 1.0);
        ADD_FAILURE() << "no exception";
      } catch (const InvalidInput& e) {
        EXPECT_NE(std::string(e.what()).find("2,147,483,649 face samples is more than the 2^31"),
                  std::string::npos)
            << e.what();
      }
      EXPECT_THROW(SampleSequence(m, o, 1.0), InvalidInput);
    }
    if (faces == FaceSampling::kMonteCarlo) {
      o.vertices = false;
      EXPECT_THROW(monte_carlo_samples(m, o), InvalidInput);
    }
  }
}

// A sample set that cannot fit in this machine's memory is refused before it is made, saying
// what it needs (vertices and 2^31 Monte Carlo samples: 72 bytes each, about 144 GiB).
TEST(Sampling, ASampleSetBeyondTheMemoryIsRefusedBeforeItIsMade) {
  const double needed = std::ldexp(1.0, 31) * sizeof(Sample);
  if (fits_in_memory(needed)) GTEST_SKIP() << "this machine has room for 2^31 samples";
  SamplingOptions o;
  o.vertices = true;
  o.faces = FaceSampling::kMonteCarlo;
  o.target_count = std::size_t{1} << 31;
  try {
    sample_surface(test::grid(4), o, 1.0);
    FAIL() << "no exception";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("samples need about"), std::string::npos) << e.what();
  }
}

// A needle far longer than the mesh's other faces is not counted to the end while the step is
// searched (found by fuzz_nearest_point: a needle of 1e100 made the count loop for ever; a
// regression shows as a test timeout). A needle 1e12 long on unit faces: no step the search may
// try gives about the target (every one gives more than 64 times it), which is refused with a
// clear error, stored or made on demand, as is a step given that makes more than 2^31 samples.
// A needle 1e4 long only shares the count: the step found is the plain search's.
TEST(Sampling, ANeedleIsNotCountedToTheEndWhileTheStepIsSearched) {
  auto with_needle = [](double length) {
    TriMesh m = test::grid(10);
    const auto base = static_cast<std::uint32_t>(m.positions.size());
    m.positions.push_back({0, 0, 1});
    m.positions.push_back({length, 0, 1});
    m.positions.push_back({0, 1e-30, 1});
    m.faces.push_back({base, base + 1, base + 2});
    return m;
  };
  SamplingOptions o;
  o.target_count = 500;
  o.threads = 2;
  const TriMesh far = with_needle(1e12);
  EXPECT_THROW(sample_surface(far, o, 1.0), InvalidInput);
  EXPECT_THROW(SampleSequence(far, o, 1.0), InvalidInput);
  o.step = 1.0;  // 1e12 samples on the needle alone
  EXPECT_THROW(sample_surface(far, o, 1.0), InvalidInput);
  EXPECT_THROW(SampleSequence(far, o, 1.0), InvalidInput);
  o.step = 0.0;
  const TriMesh near = with_needle(1e4);
  const SampleSet set = sample_surface(near, o, 1.0);
  EXPECT_EQ(set.step, detail::solve_scan_step(near, 500, 1, false));
  EXPECT_NEAR(static_cast<double>(set.face_count), 500.0, 1.0 + 0.002 * 500);
  EXPECT_EQ(SampleSequence(near, o, 1.0).size(), set.samples.size());
}

// Monte Carlo sampling of a mesh whose area overflows double (a face 1e100 wide: its squared cross
// product overflows) is refused with a clear error, stored or made on demand, where the counts
// were inf / inf, cast to an integer (found by fuzz_nearest_point under UBSan).
TEST(Sampling, MonteCarloRefusesAnAreaThatOverflows) {
  TriMesh m = test::square(1e100);
  SamplingOptions o = monte_carlo_options(100);
  ASSERT_TRUE(std::isinf(surface_area(m)));
  EXPECT_THROW(sample_surface(m, o, 1.0), InvalidInput);
  EXPECT_THROW(SampleSequence(m, o, 1.0), InvalidInput);
  EXPECT_THROW(monte_carlo_samples(m, o), InvalidInput);
  m = test::square(1e50);  // area 1e100: finite, sampled
  EXPECT_NEAR(static_cast<double>(sample_surface(m, o, 1.0).samples.size()), 100.0, 2.0);
}

TEST(Sampling, EdgeSamplesCoverEveryEdgeOnce) {
  TriMesh m = test::tetrahedron();
  SamplingOptions o;
  o.vertices = false;
  o.edges = true;
  o.faces = FaceSampling::kNone;
  o.step = 100.0;  // one sample per edge, at its middle
  SampleSet set = sample_surface(m, o, 1.0);
  EXPECT_EQ(set.edge_count, 6u);
}

TEST(Sampling, PointCloudsAllowVertexSamplesOnly) {
  TriMesh cloud;
  cloud.positions = {{0, 0, 0}, {1, 0, 0}};
  SamplingOptions o;
  o.faces = FaceSampling::kNone;
  EXPECT_EQ(sample_surface(cloud, o, 1.0).samples.size(), 2u);
  o.faces = FaceSampling::kScanConversion;
  EXPECT_THROW(sample_surface(cloud, o, 1.0), InvalidInput);
}

TEST(Sampling, UnreferencedVerticesAreNotSampled) {
  TriMesh m = test::tetrahedron();
  m.positions.push_back({9, 9, 9});
  SamplingOptions o;
  o.faces = FaceSampling::kNone;
  EXPECT_EQ(sample_surface(m, o, 1.0).vertex_count, 4u);
}

}  // namespace
}  // namespace meshdev
