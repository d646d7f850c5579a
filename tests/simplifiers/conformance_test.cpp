// The conformance suite: every registered, available backend on meshes built in code, at two
// reductions. Checks the status against the stated tolerance (simplifier.h), output validity,
// the attribute channels each backend documents, and determinism.
#include <gtest/gtest.h>

#include <map>
#include <set>
#include <tuple>

#include "metric/errors.h"
#include "simplifiers/registry.h"
#include "tests/simplifiers/fixtures.h"

namespace meshdev {
namespace {

std::vector<std::string> available_backends() {
  std::vector<std::string> names;
  for (const auto& s : create_all_simplifiers())
    if (s->available()) names.push_back(s->name());
  return names;
}

using Param = std::tuple<std::string, std::string, double>;  // backend, fixture, ratio

class Conformance : public ::testing::TestWithParam<Param> {
 protected:
  void SetUp() override {
    std::tie(backend_, fixture_, ratio_) = GetParam();
    input_ = test::fixture(fixture_);
    simplifier_ = create_simplifier(backend_);
    result_ = simplifier_->simplify(input_, SimplifyRequest::reduction(ratio_));
  }
  std::string backend_, fixture_;
  double ratio_ = 0;
  TriMesh input_;
  std::unique_ptr<Simplifier> simplifier_;
  SimplifyResult result_;
};

TEST_P(Conformance, ReachesTargetOrSaysSo) {
  EXPECT_EQ(result_.input_faces, input_.num_faces());
  EXPECT_EQ(result_.target_faces,
            resolve_target_faces(SimplifyRequest::reduction(ratio_), input_.num_faces()));
  EXPECT_EQ(result_.reached_faces, result_.mesh.num_faces());
  ASSERT_TRUE(result_.status == SimplifyStatus::kOk ||
              result_.status == SimplifyStatus::kTargetNotReached)
      << status_name(result_.status) << ": " << result_.message;
  if (result_.status == SimplifyStatus::kOk) {
    EXPECT_TRUE(target_reached(result_.reached_faces, result_.target_faces))
        << result_.reached_faces << " faces for target " << result_.target_faces;
  } else {
    EXPECT_FALSE(target_reached(result_.reached_faces, result_.target_faces));
    EXPECT_FALSE(result_.message.empty());
    EXPECT_LT(result_.reached_faces, input_.num_faces() + 1);
  }
  EXPECT_GE(result_.wall_seconds, 0.0);
}

TEST_P(Conformance, OutputIsValid) {
  const TriMesh& out = result_.mesh;
  EXPECT_NO_THROW(validate(out, "simplified"));
  for (const Vec3& p : out.positions) EXPECT_TRUE(is_finite(p));
  for (const Triangle& t : out.faces) {
    for (std::uint32_t i : t) EXPECT_LT(i, out.num_vertices());
    EXPECT_TRUE(t[0] != t[1] && t[1] != t[2] && t[0] != t[2]);
  }
  // The documented guarantees (simplifier.h OutputGuarantees).
  OutputGuarantees g = simplifier_->guarantees();
  std::size_t zero_area = test::zero_area_faces(out);
  if (g.no_new_degenerate) {
    EXPECT_LE(zero_area, test::zero_area_faces(input_));
  } else if (zero_area > 0) {
    EXPECT_NE(result_.message.find("zero-area"), std::string::npos) << "not reported";
  }
  if (g.manifold && test::max_faces_per_edge(input_) <= 2) {
    EXPECT_LE(test::max_faces_per_edge(out), 2u);
  }
  // No unreferenced vertices are left behind.
  for (bool used : referenced_vertices(out)) EXPECT_TRUE(used);
}

TEST_P(Conformance, CarriesAttributesAsDocumented) {
  // Every input channel is either kept (present, same kind/storage/dim) or listed as dropped.
  for (const AttributeChannel& c : input_.channels) {
    bool kept = std::count(result_.kept.begin(), result_.kept.end(), c.name) > 0;
    bool dropped = std::count(result_.dropped.begin(), result_.dropped.end(), c.name) > 0;
    EXPECT_NE(kept, dropped) << c.name;
    const AttributeChannel* o = result_.mesh.channel(c.name);
    if (!kept) {
      EXPECT_EQ(o, nullptr) << c.name;
      continue;
    }
    ASSERT_NE(o, nullptr) << c.name;
    EXPECT_EQ(o->kind, c.kind);
    EXPECT_EQ(o->storage, c.storage);
    EXPECT_EQ(o->dim, c.dim);
  }
  // Backends that keep vertices in place carry the values of the input vertex at that position;
  // a per-corner value must be one that vertex had in the input (seams kept, no mixing).
  if (!simplifier_->guarantees().vertices_fixed) return;
  std::map<std::tuple<double, double, double>, std::size_t> input_vertex;
  for (std::size_t v = 0; v < input_.num_vertices(); ++v) {
    const Vec3& p = input_.positions[v];
    input_vertex[{p.x, p.y, p.z}] = v;
  }
  for (const AttributeChannel& c : input_.channels) {
    const AttributeChannel* o = result_.mesh.channel(c.name);
    if (o == nullptr || c.kind == AttributeKind::kNormal) continue;  // normals are recomputed
    std::map<std::size_t, std::set<std::vector<double>>> corner_values;
    if (c.storage == Storage::kPerCorner)
      for (std::size_t f = 0; f < input_.num_faces(); ++f)
        for (int k = 0; k < 3; ++k) {
          const double* x = c.element(3 * f + k);
          corner_values[input_.faces[f][k]].insert(std::vector<double>(x, x + c.dim));
        }
    const TriMesh& out = result_.mesh;
    for (std::size_t f = 0; f < out.num_faces(); ++f)
      for (int k = 0; k < 3; ++k) {
        const Vec3& p = out.positions[out.faces[f][k]];
        auto it = input_vertex.find({p.x, p.y, p.z});
        if (it == input_vertex.end()) continue;  // a moved vertex: nothing to compare
        if (c.storage == Storage::kPerVertex) {
          const double* x = o->element(out.faces[f][k]);
          EXPECT_EQ(std::vector<double>(x, x + c.dim),
                    std::vector<double>(c.element(it->second), c.element(it->second) + c.dim))
              << c.name << " at output vertex " << out.faces[f][k];
        } else if (c.storage == Storage::kPerCorner) {
          const double* x = o->element(3 * f + k);
          EXPECT_EQ(corner_values[it->second].count(std::vector<double>(x, x + c.dim)), 1u)
              << c.name << " at face " << f << " corner " << k;
        }
      }
  }
}

TEST_P(Conformance, IsDeterministic) {
  auto again = create_simplifier(backend_)->simplify(input_, SimplifyRequest::reduction(ratio_));
  ASSERT_EQ(again.status, result_.status);
  EXPECT_EQ(again.mesh.positions, result_.mesh.positions);
  EXPECT_EQ(again.mesh.faces, result_.mesh.faces);
  ASSERT_EQ(again.mesh.channels.size(), result_.mesh.channels.size());
  for (std::size_t i = 0; i < again.mesh.channels.size(); ++i)
    EXPECT_EQ(again.mesh.channels[i].values, result_.mesh.channels[i].values);
}

std::string param_name(const ::testing::TestParamInfo<Param>& info) {
  std::string s = std::get<0>(info.param) + "_" + std::get<1>(info.param) + "_" +
                  std::to_string(static_cast<int>(std::get<2>(info.param) * 100));
  for (char& c : s)
    if (!isalnum(static_cast<unsigned char>(c))) c = '_';
  return s;
}

// A build with every backend compiled out has nothing to instantiate.
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(Conformance);

INSTANTIATE_TEST_SUITE_P(AllBackends, Conformance,
                         ::testing::Combine(::testing::ValuesIn(available_backends()),
                                            ::testing::Values("icosphere4", "grid20", "grid20_seam",
                                                              "tetrahedron"),
                                            ::testing::Values(0.5, 0.9)),
                         param_name);

// Bad requests are exceptions, for every backend (available or not).
TEST(ConformanceInput, BadRequestsThrow) {
  TriMesh mesh = test::fixture("tetrahedron");
  for (const auto& s : create_all_simplifiers()) {
    if (!s->available()) continue;
    EXPECT_THROW(s->simplify(mesh, SimplifyRequest::reduction(1.0)), InvalidInput) << s->name();
    EXPECT_THROW(s->simplify(mesh, SimplifyRequest::faces(0)), InvalidInput) << s->name();
    EXPECT_THROW(s->simplify(TriMesh{}, SimplifyRequest::faces(1)), InvalidInput) << s->name();
  }
}

}  // namespace
}  // namespace meshdev
