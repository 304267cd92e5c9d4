// The initial-packing check on hand-built particles: overlaps of known depth, touching without
// overlap, coincident centres and non-finite values, each found by hand geometry.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "tfdem/packing_check.h"

namespace {

tfdem::ParticleView view(const std::vector<double> &x, const std::vector<double> &v, const std::vector<double> &d) {
  tfdem::ParticleView p;
  p.count = d.size();
  p.position = x.data();
  p.velocity = v.data();
  p.diameter = d.data();
  return p;
}

TEST(PackingCheck, OverlapsOfKnownDepth) {
  // spheres of 1 m (positions exact in binary): a-b 0.875 apart (overlap 0.125), b-c 1 apart
  // (touching, no overlap), d of 2 m 1.25 above c (overlap (1 + 2)/2 - 1.25 = 0.25); b-d are
  // sqrt(1 + 1.5625) = 1.6 apart, beyond their reach of 1.5
  const std::vector<double> x = {0, 0, 0, 0.875, 0, 0, 1.875, 0, 0, 1.875, 1.25, 0};
  const std::vector<double> v(12, 0.0), d = {1, 1, 1, 2};
  const tfdem::PackingCheck c = tfdem::check_packing(view(x, v, d));
  EXPECT_TRUE(c.not_finite.empty());
  EXPECT_TRUE(c.coincident.empty());
  ASSERT_EQ(c.overlaps.size(), 2u);
  for (const auto &o : c.overlaps) {
    if (o.a == 0) {
      EXPECT_EQ(o.b, 1u);
      EXPECT_EQ(o.depth, 0.125);
    } else {
      EXPECT_EQ(o.a, 2u);
      EXPECT_EQ(o.b, 3u);
      EXPECT_EQ(o.depth, 0.25);
    }
  }
}

TEST(PackingCheck, CoincidentCentresAndNonFiniteValues) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<double> x = {0.01, 0.02, 0.0, 0.01, 0.02, 0.0, 0.05, 0.05, 0.0, 0.08, nan, 0.0};
  std::vector<double> v(12, 0.0);
  v[7] = std::numeric_limits<double>::infinity();  // particle 2's y velocity
  const std::vector<double> d(4, 2.5e-3);
  const tfdem::PackingCheck c = tfdem::check_packing(view(x, v, d));
  EXPECT_EQ(c.not_finite, (std::vector<std::size_t>{2, 3}));
  ASSERT_EQ(c.coincident.size(), 1u);
  EXPECT_EQ(c.coincident[0], (std::pair<std::size_t, std::size_t>{0, 1}));
  ASSERT_EQ(c.overlaps.size(), 1u);
  EXPECT_DOUBLE_EQ(c.overlaps[0].depth, 2.5e-3);
}

}  // namespace
