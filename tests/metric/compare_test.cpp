#include "metric/compare.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <iterator>
#include <string>

#include "metric/errors.h"
#include "metric/memory_limit.h"
#include "tests/support/shapes.h"

namespace meshdev {
namespace {

std::size_t measure_index(const ComparisonResult& r, const std::string& name) {
  for (std::size_t m = 0; m < r.measures.size(); ++m)
    if (r.measures[m].name == name) return m;
  ADD_FAILURE() << "no measure " << name;
  return 0;
}

CompareOptions all_sample_kinds() {
  CompareOptions o;
  o.sampling.edges = true;
  o.sampling.target_count = 5000;
  return o;
}

TEST(Compare, PlaneAgainstOffsetPlaneIsTheOffsetEverywhere) {
  TriMesh a = test::grid(8, 1.0, 0.0), b = test::grid(5, 1.0, 0.5);
  ComparisonResult r = compare_meshes(a, b, all_sample_kinds());
  for (const DirectionResult* d : {&*r.forward, &*r.backward}) {
    const Statistics& g = d->stats[0];
    EXPECT_NEAR(g.min, 0.5, 1e-15);
    EXPECT_NEAR(g.max, 0.5, 1e-15);
    EXPECT_NEAR(g.mean, 0.5, 1e-15);
    EXPECT_NEAR(g.stddev, 0.0, 1e-12);
  }
  EXPECT_NEAR(r.symmetric[0].hausdorff, 0.5, 1e-15);
  // Both planes are flat: normals agree everywhere.
  EXPECT_NEAR(r.forward->stats[measure_index(r, "normal_angle")].max, 0.0, 1e-6);
}

// Icosahedron inscribed in the unit sphere: its vertices are on the sphere (distance 0) and its
// face centres are at the inradius 0.7946544722917661, i.e. 0.2053455277 inside.
TEST(Compare, InscribedIcosahedronAgainstTheSphereHasTheKnownMinAndMax) {
  TriMesh ico = test::icosahedron(), sphere = test::icosphere(5);
  CompareOptions o;
  o.direction = Direction::kForward;
  o.sampling.step = 0.01;
  ComparisonResult r = compare_meshes(ico, sphere, o);
  EXPECT_EQ(r.forward->stats[0].min, 0.0);  // icosahedron vertices are icosphere vertices
  // The icosphere lies inside the true sphere by at most its sagitta: the largest gap between
  // the unit sphere and a face plane. So the maximum is in [exact - sagitta, exact].
  double sagitta = 0.0;
  for (const Triangle& t : sphere.faces) {
    const Vec3 &p = sphere.positions[t[0]], &q = sphere.positions[t[1]],
               &s = sphere.positions[t[2]];
    const Vec3 n = cross(q - p, s - p);
    sagitta = std::max(sagitta, 1.0 - dot(n, p) / norm(n));
  }
  const double exact = 1.0 - 0.7946544722917661;
  EXPECT_LE(r.forward->stats[0].max, exact + 1e-12);
  EXPECT_GE(r.forward->stats[0].max, exact - sagitta);
  EXPECT_LT(sagitta, 5e-4);
  EXPECT_EQ(r.forward->max_location[0].kind, SampleKind::kFace);
}

TEST(Compare, IdenticalMeshesGiveExactlyZeroForEveryAttribute) {
  TriMesh m = test::icosphere(2);
  AttributeChannel& color = m.add_channel("color", AttributeKind::kColor, Storage::kPerVertex, 3);
  for (std::size_t i = 0; i < color.values.size(); ++i)
    color.values[i] = static_cast<double>(i % 7) / 7.0;
  AttributeChannel& uv =
      m.add_channel("texcoord", AttributeKind::kTexCoord, Storage::kPerCorner, 2);
  for (std::size_t i = 0; i < uv.values.size(); ++i)
    uv.values[i] = static_cast<double>(i % 13) / 13.0;  // seams everywhere
  AttributeChannel& t =
      m.add_channel("temperature", AttributeKind::kScalar, Storage::kPerVertex, 1);
  for (std::size_t i = 0; i < t.values.size(); ++i) t.values[i] = 20.0 + static_cast<double>(i);
  for (FaceSampling faces : {FaceSampling::kScanConversion, FaceSampling::kMonteCarlo}) {
    CompareOptions o = all_sample_kinds();
    o.sampling.faces = faces;
    ComparisonResult r = compare_meshes(m, m, o);
    ASSERT_EQ(r.measures.size(), 8u);  // geometry, normal x2, color x3, texcoord, temperature
    for (std::size_t k = 0; k < r.measures.size(); ++k) {
      EXPECT_EQ(r.forward->stats[k].max, 0.0) << r.measures[k].name;
      EXPECT_EQ(r.backward->stats[k].max, 0.0) << r.measures[k].name;
    }
  }
}

TEST(Compare, TranslatedCopyHasHausdorffEqualToTheTranslation) {
  TriMesh a = test::tetrahedron();
  const Vec3 t{0.03, -0.02, 0.05};
  TriMesh b = test::translated(a, t);
  ComparisonResult r = compare_meshes(a, b, all_sample_kinds());
  EXPECT_NEAR(r.symmetric[0].hausdorff, norm(t), 1e-12);
  EXPECT_LE(r.forward->stats[0].max, norm(t) + 1e-12);
}

// A triangle halfway between two parallel triangles: every sample has two equidistant nearest
// points. The far-coloured face has the lower index, so only the tie rule gives 0.1.
TEST(Compare, TieRuleTakesTheMinimumAttributeDistance) {
  TriMesh a, b;
  a.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  a.faces = {{0, 1, 2}};
  b.positions = {{-1, -1, 1}, {3, -1, 1}, {-1, 3, 1}, {-1, -1, -1}, {3, -1, -1}, {-1, 3, -1}};
  b.faces = {{0, 1, 2}, {3, 4, 5}};
  a.add_channel("color", AttributeKind::kColor, Storage::kPerVertex, 3).values = {1, 0, 0, 1, 0,
                                                                                  0, 1, 0, 0};
  b.add_channel("color", AttributeKind::kColor, Storage::kPerFace, 3).values = {0, 0, 1, 0.9, 0, 0};
  CompareOptions o;
  o.direction = Direction::kForward;
  o.sampling.step = 0.1;
  o.attributes.attributes = {"color"};
  o.keep_samples = true;
  ComparisonResult r = compare_meshes(a, b, o);
  const std::size_t c = measure_index(r, "color");
  EXPECT_NEAR(r.forward->stats[c].min, 0.1, 1e-12);
  EXPECT_NEAR(r.forward->stats[c].max, 0.1, 1e-12);
  EXPECT_EQ(r.forward->samples_with_ties, r.forward->samples);
  EXPECT_EQ(r.forward->deviations.tie_count[0], 2u);
}

// A square whose diagonal is a UV seam: the two faces give the shared corners different UVs.
// Samples on the seam find the matching side among the tied faces, so the deviation is 0; a
// per-vertex interpolation would see the jump.
TEST(Compare, WedgeUvSeamIsComparedPerCorner) {
  TriMesh m = test::square();  // faces {0,1,3}, {0,3,2}; diagonal 0-3 is shared
  AttributeChannel& uv =
      m.add_channel("texcoord", AttributeKind::kTexCoord, Storage::kPerCorner, 2);
  uv.values = {0,   0,   0.5, 0,   0.5, 0.5,   // face 0 in the left half of the texture
               0.6, 0.1, 1.0, 0.5, 0.6, 0.5};  // face 1 in the right half
  TriMesh shifted = m;                         // B: the same, but face 1's UVs moved by 0.25 in u
  for (int k = 6; k < 12; k += 2) shifted.channel("texcoord")->values[k] += 0.25;
  CompareOptions o = all_sample_kinds();
  o.direction = Direction::kForward;
  o.attributes.attributes = {"texcoord"};
  ComparisonResult same = compare_meshes(m, m, o);
  EXPECT_EQ(same.forward->stats[1].max, 0.0);
  ComparisonResult moved = compare_meshes(m, shifted, o);
  EXPECT_NEAR(moved.forward->stats[1].max, 0.25, 1e-12);
  EXPECT_EQ(moved.forward->stats[1].min, 0.0);  // face-0 samples and seam samples still match
}

TEST(Compare, BvhAndBruteForceGiveIdenticalResults) {
  TriMesh a = test::icosphere(2), b = test::random_soup(300, 5);
  CompareOptions o = all_sample_kinds();
  o.keep_samples = true;
  ComparisonResult fast = compare_meshes(a, b, o);
  o.index = IndexKind::kBruteForce;
  ComparisonResult slow = compare_meshes(a, b, o);
  for (const auto& [x, y] :
       {std::pair{&*fast.forward, &*slow.forward}, std::pair{&*fast.backward, &*slow.backward}})
    for (std::size_t m = 0; m < fast.measures.size(); ++m)
      ASSERT_EQ(x->deviations.values[m], y->deviations.values[m]) << fast.measures[m].name;
}

// A mesh's summary box is that of the vertices its faces use (an unreferenced vertex far away
// does not count), and a mesh without faces (a point cloud) is boxed by all its vertices.
TEST(Compare, SummaryBoxHoldsTheReferencedVerticesOnly) {
  TriMesh m = test::square();
  m.positions.push_back({1e9, -1e9, 5});  // referenced by no face
  const MeshSummary s = summarize(m, "m");
  const BoundingBox box = bounding_box(test::square());
  EXPECT_EQ(s.referenced_vertices, m.positions.size() - 1);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(s.box.min[k], box.min[k]) << k;
    EXPECT_EQ(s.box.max[k], box.max[k]) << k;
  }
  TriMesh cloud;
  cloud.positions = {{0, 0, 0}, {2, -1, 3}};
  const MeshSummary c = summarize(cloud, "cloud");
  EXPECT_EQ(c.box.max[0], 2.0);
  EXPECT_EQ(c.box.min[1], -1.0);
  EXPECT_EQ(c.box.max[2], 3.0);
}

TEST(Compare, OneThreadEqualsTwoThreads) {
  TriMesh a = test::icosphere(3), b = test::translated(test::icosphere(2), {0.01, 0, 0});
  CompareOptions o = all_sample_kinds();
  o.sampling.faces = FaceSampling::kMonteCarlo;
  o.sampling.target_count = 40000;
  o.keep_samples = true;
  o.threads = 1;
  ComparisonResult one = compare_meshes(a, b, o);
  o.threads = 2;
  ComparisonResult two = compare_meshes(a, b, o);
  for (std::size_t m = 0; m < one.measures.size(); ++m) {
    ASSERT_EQ(one.forward->deviations.values[m], two.forward->deviations.values[m]);
    ASSERT_EQ(one.backward->deviations.values[m], two.backward->deviations.values[m]);
    EXPECT_EQ(one.symmetric[m].mean, two.symmetric[m].mean);
    // The statistics of 40,000 samples run in two blocks, on one thread and then on two.
    for (const auto& [x, y] : {std::pair{&one.forward->stats[m], &two.forward->stats[m]},
                               std::pair{&one.backward->stats[m], &two.backward->stats[m]}}) {
      const double got1[] = {x->mean, x->variance, x->rms, x->p50, x->p90, x->p95, x->p99, x->max};
      const double got2[] = {y->mean, y->variance, y->rms, y->p50, y->p90, y->p95, y->p99, y->max};
      for (int k = 0; k < 8; ++k)
        EXPECT_EQ(got1[k], got2[k]) << one.measures[m].name << " field " << k;
      EXPECT_EQ(x->argmax, y->argmax);
      EXPECT_EQ(x->histogram.counts, y->histogram.counts);
      EXPECT_EQ(x->histogram.weight_fraction, y->histogram.weight_fraction);
    }
  }
}

// Both directions (those that ran) of two comparisons of the same meshes give the same numbers,
// bit for bit.
void expect_same_directions(const ComparisonResult& made, const ComparisonResult& stored) {
  for (const auto& [dx, dy] :
       {std::pair{&made.forward, &stored.forward}, std::pair{&made.backward, &stored.backward}}) {
    ASSERT_EQ(dx->has_value(), dy->has_value());
    if (!dx->has_value()) continue;
    const DirectionResult *x = &**dx, *y = &**dy;
    EXPECT_EQ(x->samples, y->samples);
    EXPECT_EQ(x->sampling, y->sampling);
    EXPECT_EQ(x->step, y->step);
    EXPECT_EQ(x->index, y->index);
    EXPECT_EQ(x->nearest_feature, y->nearest_feature);
    EXPECT_EQ(x->samples_with_ties, y->samples_with_ties);
    for (std::size_t m = 0; m < made.measures.size(); ++m) {
      const Statistics &s = x->stats[m], &t = y->stats[m];
      const double got1[] = {s.min, s.mean, s.variance, s.rms, s.p50, s.p95, s.p99, s.max};
      const double got2[] = {t.min, t.mean, t.variance, t.rms, t.p50, t.p95, t.p99, t.max};
      for (int k = 0; k < 8; ++k) EXPECT_EQ(got1[k], got2[k]) << made.measures[m].name << " " << k;
      EXPECT_EQ(s.argmax, t.argmax);
      EXPECT_EQ(s.histogram.counts, t.histogram.counts);
      EXPECT_EQ(x->max_location[m].sample, y->max_location[m].sample);
      EXPECT_EQ(x->max_location[m].point, y->max_location[m].point);
      EXPECT_EQ(x->max_location[m].nearest, y->max_location[m].nearest);
      EXPECT_EQ(x->max_location[m].nearest_face, y->max_location[m].nearest_face);
    }
  }
}

// Samples without edges (Monte Carlo alone, the default vertices and scan conversion, scan
// conversion with a step, vertices alone) are made as they are queried where no per-sample output
// is kept, and stored where it is (keep_samples): the same statistics and maximum locations
// either way.
TEST(Compare, SamplesMadeAsQueriedEqualStoredOnes) {
  TriMesh a = test::icosphere(3), b = test::translated(test::icosphere(2), {0.01, 0, 0});
  for (const char* kinds : {"montecarlo", "vertices,faces", "faces", "vertices"}) {
    SCOPED_TRACE(kinds);
    CompareOptions o;
    set_sample_kinds(o.sampling, kinds);
    o.sampling.target_count = 30000;
    if (std::string(kinds) == "faces") o.sampling.step_fraction = 0.004;
    o.threads = 2;
    const ComparisonResult made = compare_meshes(a, b, o);
    o.keep_samples = true;
    const ComparisonResult stored = compare_meshes(a, b, o);
    ASSERT_FALSE(stored.forward->sample_set.samples.empty());
    expect_same_directions(made, stored);
  }
}

// A mesh with a per-vertex scalar channel "temperature" (a linear function of the position).
TriMesh with_temperature(TriMesh m) {
  AttributeChannel& c =
      m.add_channel("temperature", AttributeKind::kScalar, Storage::kPerVertex, 1);
  for (std::size_t v = 0; v < m.positions.size(); ++v)
    c.values[v] = m.positions[v][2] + 0.5 * m.positions[v][0];
  return m;
}

// One reference A compared with several meshes B, the options changed between some of the
// comparisons: each gives what a fresh comparison gives, and what A's reference keeps is used
// again exactly where the options that made it are unchanged.
TEST(Compare, ReferenceGivesWhatFreshComparisonsGive) {
  const TriMesh a = with_temperature(test::icosphere(2));  // 320 faces
  const TriMesh small = with_temperature(test::icosphere(1));
  const TriMesh moved = with_temperature(test::translated(test::icosahedron(), {0.02, 0, 0.01}));
  const TriMesh larger = with_temperature(test::icosphere(3));  // more faces than A
  ComparisonReference reference(a, "A", 2);
  CompareOptions o;
  o.threads = 2;
  struct Step {
    const TriMesh* b;
    std::function<void(CompareOptions&)> change;
    bool samples_reused, index_reused;  // expected
  };
  const Step steps[] = {
      {&small, [](CompareOptions&) {}, false, false},
      {&moved, [](CompareOptions&) {}, true, true},
      // 10 x the faces of B now: A's samples made anew, its index kept
      {&larger, [](CompareOptions&) {}, false, true},
      {&moved, [](CompareOptions& x) { x.attributes.normals = NormalSource::kArea; }, false, true},
      {&moved, [](CompareOptions&) {}, true, true},
      {&small, [](CompareOptions& x) { x.index = IndexKind::kBruteForce; }, true, false},
      {&small, [](CompareOptions& x) { x.index = IndexKind::kBvh; }, true, false},
      {&small, [](CompareOptions& x) { x.ties.relative = 1e-2; }, true, false},
      {&small, [](CompareOptions& x) { x.ties.absolute_fraction = 1e-3; }, true, false},
      {&moved,
       [](CompareOptions& x) {
         x.sampling.faces = FaceSampling::kMonteCarlo;
         x.sampling.seed = 3;
       },
       false, true},
      {&moved, [](CompareOptions& x) { x.sampling.seed = 4; }, false, true},
      {&moved, [](CompareOptions& x) { x.sampling.faces = FaceSampling::kScanConversion; }, false,
       true},
      {&moved, [](CompareOptions& x) { x.sampling.vertices = false; }, false, true},
      {&moved, [](CompareOptions& x) { x.sampling.step_fraction = 0.02; }, false, true},
      {&moved, [](CompareOptions& x) { x.sampling.step = 0.03; }, false, true},
      {&moved, [](CompareOptions& x) { x.sampling.vertices = true; }, false, true},
      {&moved, [](CompareOptions& x) { x.direction = Direction::kForward; }, true, true},
      {&small, [](CompareOptions& x) { x.direction = Direction::kBackward; }, true, true},
      {&small, [](CompareOptions& x) { x.keep_samples = true; }, false, true},
  };
  for (std::size_t i = 0; i < std::size(steps); ++i) {
    SCOPED_TRACE("step " + std::to_string(i));
    steps[i].change(o);
    const ComparisonResult fresh = compare_meshes(a, *steps[i].b, o, "A", "B");
    const ComparisonResult kept = compare_meshes(reference, *steps[i].b, o, "B");
    ASSERT_EQ(kept.measures.size(), fresh.measures.size());
    for (std::size_t m = 0; m < kept.measures.size(); ++m)
      EXPECT_EQ(kept.measures[m].name, fresh.measures[m].name);
    EXPECT_EQ(kept.normal_source, fresh.normal_source);
    EXPECT_EQ(kept.a.label, "A");
    EXPECT_EQ(kept.a.faces, fresh.a.faces);
    EXPECT_EQ(kept.a.area, fresh.a.area);
    EXPECT_EQ(kept.diagonal, fresh.diagonal);
    expect_same_directions(kept, fresh);
    for (std::size_t m = 0; m < kept.symmetric.size(); ++m)
      EXPECT_EQ(kept.symmetric[m].mean, fresh.symmetric[m].mean);
    if (kept.forward && !o.keep_samples) {
      EXPECT_EQ(kept.forward->samples_reused, steps[i].samples_reused);
    }
    if (kept.backward) {
      EXPECT_EQ(kept.backward->index_reused, steps[i].index_reused);
    }
    for (const auto* d : {&fresh.forward, &fresh.backward}) {
      if (d->has_value()) {
        EXPECT_FALSE((*d)->samples_reused || (*d)->index_reused);
      }
    }
  }
}

// A reference is checked when made, and a mesh B compared with it is checked as compare_meshes
// checks it: the same errors.
TEST(Compare, ReferenceRejectsWhatCompareMeshesRejects) {
  TriMesh broken = test::square();
  broken.faces[0][1] = 99;  // out of range
  EXPECT_THROW(ComparisonReference(broken, "broken"), InvalidInput);
  EXPECT_THROW(ComparisonReference(TriMesh(), "empty"), InvalidInput);
  const TriMesh a = test::icosphere(1);
  ComparisonReference reference(a, "A");
  EXPECT_THROW(compare_meshes(reference, broken, CompareOptions(), "broken"), InvalidInput);
  TriMesh cloud;
  cloud.positions = {{0, 0, 0}};
  CompareOptions o;
  try {
    compare_meshes(reference, cloud, o, "cloud");
    ADD_FAILURE() << "a mesh without faces was searched";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("cloud has no faces"), std::string::npos) << e.what();
  }
  // The reference still works after a failed comparison.
  const ComparisonResult r = compare_meshes(reference, a, o, "A again");
  EXPECT_EQ(r.forward->stats[0].max, 0.0);
  EXPECT_EQ(r.backward->stats[0].max, 0.0);
}

// A comparison whose per-sample results cannot fit in this machine's memory is refused before
// B's index is built or any query made, saying what it needs: 2^31 Monte Carlo samples, made on
// demand (no sample set), about 29 bytes of results each.
TEST(Compare, ASampleCountBeyondTheMemoryIsRefusedBeforeAnyWork) {
  CompareOptions o;
  o.sampling.vertices = false;
  o.sampling.faces = FaceSampling::kMonteCarlo;
  o.sampling.target_count = std::size_t{1} << 31;
  if (fits_in_memory(std::ldexp(29.0, 31)))
    GTEST_SKIP() << "this machine has room for the results of 2^31 samples";
  try {
    compare_meshes(test::icosphere(2), test::icosphere(1), o, "A", "B");
    FAIL() << "no exception";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("the deviations of 21474836"), std::string::npos)
        << e.what();
  }
}

// Option values out of range give InvalidInput naming the option, never a crash, an exception of
// another type or a silent result (a billion histogram bins ended in std::bad_alloc, 100,000
// threads and tie tolerances of 0 in crashes, a step of 1e-300 read "0.000000" in its message).
TEST(Compare, OptionsOutOfRangeAreRejectedByName) {
  const TriMesh a = test::icosphere(2), b = test::icosphere(1);
  struct Case {
    std::function<void(CompareOptions&)> set;
    const char* expected;  // in the message
  };
  const Case cases[] = {
      {[](CompareOptions& o) { o.histogram_bins = 0; }, "histogram_bins"},
      {[](CompareOptions& o) { o.histogram_bins = -5; }, "histogram_bins"},
      {[](CompareOptions& o) { o.histogram_bins = 1000000000; }, "histogram_bins"},
      {[](CompareOptions& o) { o.threads = -1; }, "threads must be between 0"},
      {[](CompareOptions& o) { o.threads = 100000; }, "threads must be between 0"},
      {[](CompareOptions& o) { o.ties.relative = -1e-9; }, "tie tolerances"},
      {[](CompareOptions& o) { o.ties.absolute_fraction = std::nan(""); }, "tie tolerances"},
      {[](CompareOptions& o) { o.sampling.step = 1e-300; }, "step 1e-300 would"},
      {[](CompareOptions& o) { o.sampling.step = -1; }, "sampling step"},
      {[](CompareOptions& o) { o.sampling.target_count = (std::size_t{1} << 31) + 1; },
       "is more than the 2^31"},
      {[](CompareOptions& o) {
         o.sampling.edges = true;
         o.sampling.step = 1e-12;
       },
       "step 1e-12 would"},
  };
  for (std::size_t i = 0; i < std::size(cases); ++i) {
    CompareOptions o;
    cases[i].set(o);
    for (bool reference : {false, true}) {
      try {
        if (reference) {
          ComparisonReference r(a, "A");
          compare_meshes(r, b, o, "B");
        } else {
          compare_meshes(a, b, o, "A", "B");
        }
        ADD_FAILURE() << "case " << i << " was accepted";
      } catch (const InvalidInput& e) {
        EXPECT_NE(std::string(e.what()).find(cases[i].expected), std::string::npos)
            << "case " << i << ": " << e.what();
      }
    }
  }
  EXPECT_THROW(ComparisonReference(a, "A", kMaxThreads + 1), InvalidInput);
  // The bounds themselves are fine.
  CompareOptions o;
  o.histogram_bins = 1;
  EXPECT_NO_THROW(compare_meshes(a, b, o, "A", "B"));
  o.ties.relative = 0.0;
  o.ties.absolute_fraction = 0.0;
  EXPECT_NO_THROW(compare_meshes(a, b, o, "A", "B"));
}

TEST(Compare, PointCloudReferenceWorksForwardOnly) {
  TriMesh cloud;
  cloud.positions = {{0.2, 0.2, 1.0}, {0.5, 0.1, -2.0}};
  TriMesh plane = test::square();
  CompareOptions o;
  o.sampling.faces = FaceSampling::kNone;
  o.direction = Direction::kForward;
  ComparisonResult r = compare_meshes(cloud, plane, o);
  EXPECT_EQ(r.forward->stats[0].max, 2.0);
  o.direction = Direction::kBoth;
  EXPECT_THROW(compare_meshes(cloud, plane, o), InvalidInput);
}

}  // namespace
}  // namespace meshdev
