// openmesh-appearance: keeps a sharp colour boundary better than openmesh-quadric (measured with
// meshdev's own metric), optimal placement lowers the geometric error, no flips, endpoint mode
// keeps vertices fixed, sweeps equal separate runs, options are checked.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <map>
#include <tuple>

#include "metric/compare.h"
#include "metric/errors.h"
#include "simplifiers/openmesh_appearance.h"
#include "simplifiers/registry.h"
#include "tests/simplifiers/fixtures.h"
#include "tests/support/shapes.h"

namespace meshdev {
namespace {

// icosphere(5) (20 480 faces) with sharp red / blue stripes: the colour jumps between two
// neighbouring vertex rings wherever sin(5 pi z) changes sign.
TriMesh striped_sphere() {
  TriMesh m = test::icosphere(5);
  AttributeChannel& c = m.add_channel("color", AttributeKind::kColor, Storage::kPerVertex, 3);
  for (std::size_t v = 0; v < m.num_vertices(); ++v) {
    bool red = std::sin(5.0 * 3.14159265358979 * m.positions[v].z) > 0;
    c.element(v)[0] = red ? 1.0 : 0.0;
    c.element(v)[1] = 0.0;
    c.element(v)[2] = red ? 0.0 : 1.0;
  }
  return m;
}

// The symmetric mean of one measure (meshdev's metric, default sampling).
double symmetric_mean(const TriMesh& a, const TriMesh& b, const std::string& measure) {
  CompareOptions options;
  options.attributes.attributes = {measure};
  ComparisonResult r = compare_meshes(a, b, options, "input", "simplified");
  for (std::size_t i = 0; i < r.measures.size(); ++i)
    if (r.measures[i].name == measure) return r.symmetric.at(i).mean;
  ADD_FAILURE() << "no measure " << measure;
  return 0;
}

SimplifyResult run(const std::string& backend, const TriMesh& mesh, double ratio,
                   const std::map<std::string, std::string>& options = {}) {
  auto s = create_simplifier(backend);
  for (const auto& [k, v] : options) s->set_option(k, v);
  SimplifyResult r = s->simplify(mesh, SimplifyRequest::reduction(ratio));
  EXPECT_EQ(r.status, SimplifyStatus::kOk) << backend << ": " << r.message;
  return r;
}

TEST(OpenMeshAppearance, KeepsSharpColourBoundaryBetterThanQuadric) {
  TriMesh input = striped_sphere();
  SimplifyResult plain = run("openmesh-quadric", input, 0.9);
  SimplifyResult appearance = run("openmesh-appearance", input, 0.9);
  double plain_color = symmetric_mean(input, plain.mesh, "color");
  double appearance_color = symmetric_mean(input, appearance.mesh, "color");
  std::cout << "[ colour ] symmetric mean colour deviation at 90 %: openmesh-quadric "
            << plain_color << ", openmesh-appearance " << appearance_color << '\n';
  EXPECT_LT(appearance_color, 0.5 * plain_color);
  // And the geometry stays in the same league (within 3x of the plain quadric).
  double plain_geom = symmetric_mean(input, plain.mesh, "geometry");
  double appearance_geom = symmetric_mean(input, appearance.mesh, "geometry");
  std::cout << "[ geometry ] symmetric mean distance: openmesh-quadric " << plain_geom
            << ", openmesh-appearance " << appearance_geom << '\n';
  EXPECT_LT(appearance_geom, 3.0 * plain_geom);
}

TEST(OpenMeshAppearance, OptimalPlacementLowersGeometricError) {
  TriMesh input = test::icosphere_with_normals(5);
  SimplifyResult endpoint = run("openmesh-appearance", input, 0.9, {{"optimal", "false"}});
  SimplifyResult optimal = run("openmesh-appearance", input, 0.9);
  double e = symmetric_mean(input, endpoint.mesh, "geometry");
  double o = symmetric_mean(input, optimal.mesh, "geometry");
  std::cout << "[ placement ] symmetric mean distance: endpoint " << e << ", optimal " << o << '\n';
  EXPECT_LT(o, e);
}

TEST(OpenMeshAppearance, NoFaceTurnsInsideOut) {
  // On a sphere every face normal points away from the centre; a flipped face would not.
  TriMesh input = striped_sphere();
  for (double ratio : {0.9, 0.99}) {
    SimplifyResult r = run("openmesh-appearance", input, ratio);
    for (const Triangle& t : r.mesh.faces) {
      const Vec3& a = r.mesh.positions[t[0]];
      const Vec3& b = r.mesh.positions[t[1]];
      const Vec3& c = r.mesh.positions[t[2]];
      EXPECT_GT(dot(cross(b - a, c - a), a + b + c), 0.0) << "ratio " << ratio;
    }
  }
}

TEST(OpenMeshAppearance, EndpointModeKeepsVerticesAndValues) {
  TriMesh input = striped_sphere();
  std::map<std::tuple<double, double, double>, std::size_t> index;
  for (std::size_t v = 0; v < input.num_vertices(); ++v)
    index[{input.positions[v].x, input.positions[v].y, input.positions[v].z}] = v;
  SimplifyResult r = run("openmesh-appearance", input, 0.9, {{"optimal", "false"}});
  const AttributeChannel* in = input.channel("color");
  const AttributeChannel* out = r.mesh.channel("color");
  ASSERT_NE(out, nullptr);
  for (std::size_t v = 0; v < r.mesh.num_vertices(); ++v) {
    const Vec3& p = r.mesh.positions[v];
    auto it = index.find({p.x, p.y, p.z});
    ASSERT_NE(it, index.end()) << "vertex " << v << " moved";
    for (int k = 0; k < 3; ++k) EXPECT_EQ(out->element(v)[k], in->element(it->second)[k]);
  }
}

TEST(OpenMeshAppearance, OptimalColoursStayInRange) {
  SimplifyResult r = run("openmesh-appearance", striped_sphere(), 0.95);
  for (double x : r.mesh.channel("color")->values) {
    EXPECT_GE(x, 0.0);
    EXPECT_LE(x, 1.0);
  }
}

TEST(OpenMeshAppearance, SweepEqualsSeparateRuns) {
  TriMesh input = striped_sphere();
  OpenMeshAppearance s;
  std::vector<SimplifyRequest> requests = {SimplifyRequest::reduction(0.9),
                                           SimplifyRequest::reduction(0.5)};
  std::vector<SimplifyResult> sweep = s.simplify_sweep(input, requests);
  ASSERT_EQ(sweep.size(), 2u);
  for (std::size_t i = 0; i < requests.size(); ++i) {
    SimplifyResult one = OpenMeshAppearance().simplify(input, requests[i]);
    EXPECT_EQ(sweep[i].reached_faces, one.reached_faces);
    EXPECT_EQ(sweep[i].mesh.positions, one.mesh.positions);
    EXPECT_EQ(sweep[i].mesh.faces, one.mesh.faces);
    EXPECT_EQ(sweep[i].mesh.channels.at(0).values, one.mesh.channels.at(0).values);
  }
}

TEST(OpenMeshAppearance, OptionsAreChecked) {
  OpenMeshAppearance s;
  EXPECT_THROW(s.set_option("color_weight", "-1"), InvalidInput);
  EXPECT_THROW(s.set_option("optimal", "maybe"), InvalidInput);
  EXPECT_THROW(s.set_option("max_flip_deg", "0"), InvalidInput);
  EXPECT_THROW(s.set_option("nope", "1"), InvalidInput);
  s.set_option("optimal", "false");
  EXPECT_TRUE(s.guarantees().vertices_fixed);
  s.set_option("optimal", "true");
  EXPECT_FALSE(s.guarantees().vertices_fixed);
}

}  // namespace
}  // namespace meshdev
