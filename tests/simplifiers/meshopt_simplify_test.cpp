// meshoptimizer backends: counts, seams, lock_border, target_error.
#include <gtest/gtest.h>

#include "simplifiers/meshopt_simplify.h"
#include "tests/simplifiers/fixtures.h"
#include "tests/support/shapes.h"

namespace meshdev {
namespace {

TEST(Meshopt, ReachesTheTargetOnASphere) {
  TriMesh mesh = test::icosphere(4);
  SimplifyResult r =
      MeshoptSimplifier(MeshoptVariant::kSimplify).simplify(mesh, SimplifyRequest::reduction(0.9));
  EXPECT_EQ(r.status, SimplifyStatus::kOk) << r.message;
  EXPECT_LE(r.reached_faces, r.target_faces);
  EXPECT_GT(r.reached_faces, r.target_faces * 9 / 10);
  EXPECT_GT(r.backend_error, 0.0);
}

TEST(Meshopt, VerticesAreASubsetOfTheInput) {
  TriMesh mesh = test::icosphere(3);
  SimplifyResult r =
      MeshoptSimplifier(MeshoptVariant::kSimplify).simplify(mesh, SimplifyRequest::reduction(0.8));
  for (const Vec3& p : r.mesh.positions)
    EXPECT_NE(std::find(mesh.positions.begin(), mesh.positions.end(), p), mesh.positions.end());
}

TEST(Meshopt, KeepsTheUvSeam) {
  TriMesh mesh = test::grid_with_uv_seam(20);
  SimplifyResult r =
      MeshoptSimplifier(MeshoptVariant::kSimplify).simplify(mesh, SimplifyRequest::reduction(0.9));
  const AttributeChannel* uv = r.mesh.channel("texcoord");
  ASSERT_NE(uv, nullptr);
  // No output triangle mixes the two charts (u < 1 on the left chart, u >= 1 on the right one,
  // except the seam vertices which have both).
  for (std::size_t f = 0; f < r.mesh.num_faces(); ++f) {
    int left = 0, right = 0;
    for (int k = 0; k < 3; ++k) {
      double u = uv->element(3 * f + k)[0];
      double x = r.mesh.positions[r.mesh.faces[f][k]].x;
      EXPECT_TRUE(u == x || u == x + 1.0);
      (u < 1.0 && x < 0.5) ? ++left : (u >= 1.0 && x > 0.5) ? ++right : 0;
    }
    EXPECT_FALSE(left > 0 && right > 0) << "face " << f << " crosses the seam";
  }
}

TEST(Meshopt, LockBorderKeepsTheBorder) {
  TriMesh mesh = test::grid(20);
  MeshoptSimplifier s(MeshoptVariant::kSimplify);
  s.set_option("lock_border", "true");
  SimplifyResult r = s.simplify(mesh, SimplifyRequest::reduction(0.9));
  std::size_t border = 0;
  for (const Vec3& p : r.mesh.positions)
    border += (p.x == 0 || p.x == 1 || p.y == 0 || p.y == 1) ? 1 : 0;
  EXPECT_EQ(border, 80u);  // all 4 * 20 border vertices of the 21 x 21 grid survive
}

TEST(Meshopt, SmallTargetErrorStopsEarly) {
  TriMesh mesh = test::icosphere(4);
  MeshoptSimplifier s(MeshoptVariant::kSimplify);
  s.set_option("target_error", "0.001");
  SimplifyResult r = s.simplify(mesh, SimplifyRequest::reduction(0.99));
  EXPECT_EQ(r.status, SimplifyStatus::kTargetNotReached);
  EXPECT_LE(r.backend_error, 0.001 + 1e-6);
}

TEST(MeshoptSloppy, UndershootsOrHitsTheCount) {
  TriMesh mesh = test::icosphere(4);
  SimplifyResult r =
      MeshoptSimplifier(MeshoptVariant::kSloppy).simplify(mesh, SimplifyRequest::reduction(0.9));
  EXPECT_EQ(r.status, SimplifyStatus::kOk) << r.message;
  EXPECT_LE(r.reached_faces, r.target_faces + 2);
  EXPECT_GT(r.reached_faces, 0u);
}

TEST(Meshopt, PerFaceChannelsAreDroppedAndSaidSo) {
  TriMesh mesh = test::icosphere(2);
  mesh.add_channel("face_id", AttributeKind::kScalar, Storage::kPerFace, 1);
  SimplifyResult r =
      MeshoptSimplifier(MeshoptVariant::kSimplify).simplify(mesh, SimplifyRequest::reduction(0.5));
  EXPECT_EQ(r.mesh.channel("face_id"), nullptr);
  ASSERT_EQ(r.dropped.size(), 1u);
  EXPECT_NE(r.message.find("face_id"), std::string::npos);
}

}  // namespace
}  // namespace meshdev
