// The registry and the shared request/status helpers.
#include <gtest/gtest.h>

#include "metric/errors.h"
#include "simplifiers/registry.h"

namespace meshdev {
namespace {

TEST(Registry, ListsEveryBackendOnceAndCreatesIt) {
  std::vector<std::string> names = simplifier_names();
  EXPECT_GE(names.size(), 5u);
  for (const std::string& n : names) {
    EXPECT_EQ(std::count(names.begin(), names.end(), n), 1);
    auto s = create_simplifier(n);
    ASSERT_NE(s, nullptr);
    EXPECT_EQ(s->name(), n);
    EXPECT_FALSE(s->description().empty());
    EXPECT_FALSE(s->role().empty());
    if (!s->available()) {
      EXPECT_FALSE(s->unavailable_reason().empty());
    }
  }
}

TEST(Registry, UnknownNameListsTheKnownOnes) {
  try {
    create_simplifier("qslim-9000");
    FAIL() << "no exception";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("qslim-9000"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("openmesh-quadric"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("meshopt"), std::string::npos);
  }
}

TEST(Registry, UnknownOrBadOptionsThrow) {
  for (const std::string& n : simplifier_names()) {
    auto s = create_simplifier(n);
    if (!s->available()) continue;
    EXPECT_THROW(s->set_option("no_such_option", "1"), InvalidInput) << n;
    for (const OptionInfo& o : s->options()) {
      EXPECT_NO_THROW(s->set_option(o.key, o.default_value)) << n << " " << o.key;
      EXPECT_THROW(s->set_option(o.key, "banana"), InvalidInput) << n << " " << o.key;
    }
  }
}

TEST(Request, ResolvesRatiosAndCounts) {
  EXPECT_EQ(resolve_target_faces(SimplifyRequest::reduction(0.9), 1000), 100u);
  EXPECT_EQ(resolve_target_faces(SimplifyRequest::reduction(0.0), 1000), 1000u);
  EXPECT_EQ(resolve_target_faces(SimplifyRequest::reduction(0.999), 100), 1u);  // at least 1
  EXPECT_EQ(resolve_target_faces(SimplifyRequest::faces(37), 1000), 37u);
  EXPECT_THROW(resolve_target_faces(SimplifyRequest::reduction(1.0), 10), InvalidInput);
  EXPECT_THROW(resolve_target_faces(SimplifyRequest::faces(0), 10), InvalidInput);
}

TEST(Request, ToleranceIsMaxOfTwoFacesAndOnePercent) {
  EXPECT_TRUE(target_reached(100, 100));
  EXPECT_TRUE(target_reached(50, 100));  // below is fine
  EXPECT_TRUE(target_reached(102, 100));
  EXPECT_FALSE(target_reached(103, 100));
  EXPECT_TRUE(target_reached(10100, 10000));
  EXPECT_FALSE(target_reached(10101, 10000));
}

}  // namespace
}  // namespace meshdev
