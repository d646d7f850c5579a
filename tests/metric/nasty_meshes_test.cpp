// Valid but nasty meshes through compare_meshes (reliability.md §5 B1-B11, C1): every result is
// finite, the three nearest-point indexes give bit-identical per-sample values, and the values
// are the known ones where they are known.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "metric/compare.h"
#include "metric/errors.h"
#include "tests/support/shapes.h"

namespace meshdev {
namespace {

CompareOptions every_sample_kind() {
  CompareOptions o;
  o.sampling.edges = true;
  o.sampling.target_count = 2000;
  o.keep_samples = true;
  return o;
}

void expect_finite(const DirectionResult& d) {
  for (const Statistics& s : d.stats)
    for (double v : {s.min, s.max, s.mean, s.rms, s.stddev, s.p50, s.p99, s.weight_sum})
      ASSERT_TRUE(std::isfinite(v)) << d.from << "->" << d.to;
  for (const DeviationArray& values : d.deviations.values)
    for (double v : values) ASSERT_TRUE(std::isfinite(v)) << d.from << "->" << d.to;
}

// Compares with the BVH, the grid and the brute-force oracle; asserts finite results and
// bit-identical per-sample values, and returns the BVH result.
ComparisonResult compare_with_every_index(const TriMesh& a, const TriMesh& b, CompareOptions o) {
  o.keep_samples = true;
  o.index = IndexKind::kBvh;
  ComparisonResult bvh = compare_meshes(a, b, o);
  for (IndexKind kind : {IndexKind::kGrid, IndexKind::kBruteForce}) {
    o.index = kind;
    ComparisonResult other = compare_meshes(a, b, o);
    for (auto [x, y] :
         {std::pair{&bvh.forward, &other.forward}, std::pair{&bvh.backward, &other.backward}}) {
      EXPECT_EQ(x->has_value(), y->has_value());
      if (!x->has_value()) continue;
      expect_finite(**x);
      expect_finite(**y);
      EXPECT_EQ((*x)->samples, (*y)->samples);
      for (std::size_t m = 0; m < bvh.measures.size(); ++m)
        EXPECT_EQ((*x)->deviations.values[m], (*y)->deviations.values[m])
            << bvh.measures[m].name << " with index " << (*y)->index;
    }
  }
  return bvh;
}

const Statistics& geometry(const std::optional<DirectionResult>& d) {
  return d->stats[0];
}

bool measures(const ComparisonResult& r, const std::string& name) {
  for (const Measure& m : r.measures)
    if (m.name == name) return true;
  return false;
}

// The unit square at z = 0 plus, inside it, a collinear triangle along the diagonal and a
// triangle whose three corners coincide.
TriMesh square_with_degenerate_faces() {
  TriMesh m = test::square();
  const auto base = static_cast<std::uint32_t>(m.positions.size());
  m.positions.insert(m.positions.end(),
                     {{0, 0, 0}, {0.5, 0.5, 0}, {1, 1, 0}, {0.3, 0.3, 0}, {0.3, 0.3, 0}});
  m.faces.push_back({base, base + 1, base + 2});
  m.faces.push_back({base + 3, base + 4, base + 3});
  return m;
}

TEST(NastyMeshes, ZeroAreaTrianglesAsTargetGiveTheDistanceToTheSurface) {
  TriMesh plane = test::grid(4, 1.0, 0.25);
  ComparisonResult r =
      compare_with_every_index(plane, square_with_degenerate_faces(), every_sample_kind());
  EXPECT_NEAR(geometry(r.forward).min, 0.25, 1e-15);
  EXPECT_NEAR(geometry(r.forward).max, 0.25, 1e-15);
}

TEST(NastyMeshes, ZeroAreaTrianglesAsReferenceGiveTheDistanceToTheSurface) {
  TriMesh plane = test::grid(4, 1.0, 0.25);
  ComparisonResult r =
      compare_with_every_index(square_with_degenerate_faces(), plane, every_sample_kind());
  EXPECT_NEAR(geometry(r.forward).min, 0.25, 1e-15);
  EXPECT_NEAR(geometry(r.forward).max, 0.25, 1e-15);
  EXPECT_NEAR(geometry(r.backward).max, 0.25, 1e-15);
}

// A target made only of zero-area triangles: the segment from (0,0,0) to (2,0,0), as a collinear
// triangle and as a triangle with a repeated corner. A point (x, y, 1) with x in [0, 1] is at
// distance sqrt(1 + y^2) from it.
TEST(NastyMeshes, TargetOfOnlyDegenerateTrianglesIsTheirSegment) {
  TriMesh segment;
  segment.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  segment.faces = {{0, 1, 2}, {0, 2, 2}};
  CompareOptions o = every_sample_kind();
  o.direction = Direction::kForward;
  ComparisonResult r = compare_with_every_index(test::square(1.0, 1.0), segment, o);
  EXPECT_NEAR(geometry(r.forward).min, 1.0, 1e-12);
  EXPECT_NEAR(geometry(r.forward).max, std::sqrt(2.0), 1e-12);
}

// Sampling a mesh whose total area is 0: either refused with InvalidInput or finite numbers.
TEST(NastyMeshes, SampledMeshOfZeroAreaIsFiniteOrRefused) {
  TriMesh segment;
  segment.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  segment.faces = {{0, 1, 2}, {0, 2, 2}};
  CompareOptions o = every_sample_kind();
  o.direction = Direction::kForward;
  try {
    ComparisonResult r = compare_with_every_index(segment, test::square(2.0, 1.0), o);
    EXPECT_NEAR(geometry(r.forward).min, 1.0, 1e-15);
    EXPECT_NEAR(geometry(r.forward).max, 1.0, 1e-15);
  } catch (const InvalidInput&) {
  }
}

// Every vertex doubled (faces use the copies) and every face doubled: nothing changes.
TEST(NastyMeshes, DuplicateVerticesAndFacesChangeNothing) {
  TriMesh plain = test::grid(3);
  TriMesh doubled = plain;
  const auto n = static_cast<std::uint32_t>(plain.positions.size());
  doubled.positions.insert(doubled.positions.end(), plain.positions.begin(), plain.positions.end());
  for (const Triangle& t : plain.faces) doubled.faces.push_back({t[0] + n, t[1] + n, t[2] + n});
  for (const Triangle& t : plain.faces) doubled.faces.push_back(t);
  ComparisonResult same = compare_with_every_index(doubled, plain, every_sample_kind());
  EXPECT_EQ(geometry(same.forward).max, 0.0);
  EXPECT_EQ(geometry(same.backward).max, 0.0);
  ComparisonResult offset =
      compare_with_every_index(doubled, test::grid(2, 1.0, 0.5), every_sample_kind());
  EXPECT_NEAR(geometry(offset.forward).min, 0.5, 1e-15);
  EXPECT_NEAR(geometry(offset.forward).max, 0.5, 1e-15);
  EXPECT_NEAR(offset.symmetric[0].hausdorff, 0.5, 1e-15);
}

// Three triangles sharing the edge (0,0,0)-(1,0,0): a non-manifold "book".
TEST(NastyMeshes, NonManifoldEdgeIsMeasuredLikeAnyOtherSurface) {
  TriMesh book;
  book.positions = {{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {0.5, 0, 1}, {0.5, -1, 0}};
  book.faces = {{0, 1, 2}, {0, 1, 3}, {1, 0, 4}};
  ComparisonResult same = compare_with_every_index(book, book, every_sample_kind());
  for (std::size_t m = 0; m < same.measures.size(); ++m) {
    EXPECT_EQ(same.forward->stats[m].max, 0.0) << same.measures[m].name;
    EXPECT_EQ(same.backward->stats[m].max, 0.0) << same.measures[m].name;
  }
  // Against the plane z = -1 the farthest point is the page's tip (0.5, 0, 1): distance 2.
  TriMesh floor = test::translated(test::grid(4, 3.0, -1.0), {-1, -1.5, 0});
  CompareOptions o = every_sample_kind();
  o.direction = Direction::kForward;
  ComparisonResult r = compare_with_every_index(book, floor, o);
  EXPECT_NEAR(geometry(r.forward).min, 1.0, 1e-15);
  EXPECT_NEAR(geometry(r.forward).max, 2.0, 1e-15);
}

TEST(NastyMeshes, UnreferencedVerticesAreNotSampledAndDoNotWidenTheBox) {
  TriMesh with_stray = test::square();
  with_stray.positions.push_back({100, 100, 100});
  ComparisonResult r = compare_with_every_index(with_stray, test::square(), every_sample_kind());
  EXPECT_EQ(geometry(r.forward).max, 0.0);
  EXPECT_EQ(geometry(r.backward).max, 0.0);
  EXPECT_DOUBLE_EQ(r.diagonal, std::sqrt(2.0));
  EXPECT_EQ(r.a.vertices, 5u);
  EXPECT_EQ(r.a.referenced_vertices, 4u);
}

TEST(NastyMeshes, PointCloudIsAReferenceButNotATarget) {
  TriMesh cloud;
  cloud.positions = {{0.5, 0.5, 3.0}, {2.0, 0.5, 0.0}, {0.25, 0.75, 0.0}};
  CompareOptions o;
  o.sampling.faces = FaceSampling::kNone;
  o.direction = Direction::kForward;
  ComparisonResult r = compare_with_every_index(cloud, test::square(), o);
  EXPECT_EQ(r.forward->samples, 3u);
  EXPECT_EQ(geometry(r.forward).min, 0.0);
  EXPECT_EQ(geometry(r.forward).max, 3.0);
  o.direction = Direction::kBackward;
  EXPECT_THROW(compare_meshes(cloud, test::square(), o), InvalidInput);
  EXPECT_THROW(compare_meshes(test::square(), cloud, CompareOptions{}), InvalidInput);
}

// B = A moved by 10 along x: nothing is dropped for being far, and the Hausdorff distance is the
// translation.
TEST(NastyMeshes, MeshesThatDoNotOverlapKeepEverySample) {
  TriMesh a = test::square(), b = test::translated(test::square(), {10, 0, 0});
  ComparisonResult r = compare_with_every_index(a, b, every_sample_kind());
  EXPECT_EQ(r.forward->deviations.values[0].size(), r.forward->samples);
  EXPECT_NEAR(geometry(r.forward).min, 9.0, 1e-12);
  EXPECT_NEAR(geometry(r.forward).max, 10.0, 1e-12);
  EXPECT_NEAR(r.symmetric[0].hausdorff, 10.0, 1e-12);
  TriMesh far = test::translated(test::icosphere(1), {1e6, -1e6, 1e6});
  ComparisonResult rf = compare_with_every_index(test::icosphere(1), far, every_sample_kind());
  EXPECT_NEAR(rf.symmetric[0].hausdorff, std::sqrt(3.0) * 1e6, 1e-6);
}

// Offsets of 1e15 (ulp 0.125): identical meshes stay exactly 0 and a 0.5 offset stays 0.5 to
// within the coordinates' rounding.
TEST(NastyMeshes, HugeCoordinatesStayFiniteAndAccurate) {
  const Vec3 far{1e15, -1e15, 1e15};
  TriMesh a = test::translated(test::grid(3), far);
  ComparisonResult same = compare_with_every_index(a, a, every_sample_kind());
  for (std::size_t m = 0; m < same.measures.size(); ++m)
    EXPECT_EQ(same.forward->stats[m].max, 0.0) << same.measures[m].name;
  TriMesh b = test::translated(test::grid(2, 1.0, 0.5), far);
  ComparisonResult r = compare_with_every_index(a, b, every_sample_kind());
  EXPECT_NEAR(geometry(r.forward).max, 0.5, 0.25);
  EXPECT_NEAR(geometry(r.forward).min, 0.5, 0.25);
}

TEST(NastyMeshes, IdenticalMeshesGiveExactlyZeroWithEveryIndexAndSampling) {
  TriMesh m = test::icosphere(2);
  for (FaceSampling faces : {FaceSampling::kScanConversion, FaceSampling::kMonteCarlo}) {
    CompareOptions o = every_sample_kind();
    o.sampling.faces = faces;
    ComparisonResult r = compare_with_every_index(m, m, o);
    for (std::size_t k = 0; k < r.measures.size(); ++k) {
      EXPECT_EQ(r.forward->stats[k].max, 0.0) << r.measures[k].name;
      EXPECT_EQ(r.backward->stats[k].max, 0.0) << r.measures[k].name;
    }
  }
}

// The same surface with faces in reverse order and each triangle's corners rotated.
TEST(NastyMeshes, ReorderedCopyIsZeroToRounding) {
  TriMesh m = test::icosphere(2), reordered = m;
  reordered.faces.assign(m.faces.rbegin(), m.faces.rend());
  for (Triangle& t : reordered.faces) t = {t[1], t[2], t[0]};
  ComparisonResult r = compare_with_every_index(m, reordered, every_sample_kind());
  EXPECT_LE(r.symmetric[0].hausdorff, 1e-12 * r.diagonal);
}

TEST(NastyMeshes, AttributeOnOneMeshOnlyIsSkippedUnlessRequested) {
  TriMesh coloured = test::grid(2);
  AttributeChannel& c =
      coloured.add_channel("color", AttributeKind::kColor, Storage::kPerVertex, 3);
  for (std::size_t i = 0; i < c.values.size(); ++i) c.values[i] = 0.5;
  ComparisonResult r = compare_with_every_index(coloured, test::grid(3), every_sample_kind());
  EXPECT_FALSE(measures(r, "color"));
  EXPECT_LE(geometry(r.forward).max, 1e-12);  // same square, different triangulation
  CompareOptions o;
  o.attributes.attributes = {"geometry", "color"};
  EXPECT_THROW(compare_meshes(coloured, test::grid(3), o), InvalidInput);
  EXPECT_THROW(compare_meshes(test::grid(3), coloured, o), InvalidInput);
}

}  // namespace
}  // namespace meshdev
