#pragma once
// GoogleTest checks shared by the tests.
#include <gtest/gtest.h>

#include "dresskit/mesh/topology.h"

namespace dresskit::test {

/// A surface with no border, manifold and oriented outward, in `components` pieces.
inline void expect_closed_outward(const mesh::TopologyReport& t, int components = 1) {
  EXPECT_TRUE(t.manifold);
  EXPECT_TRUE(t.closed);
  EXPECT_TRUE(t.outward);
  EXPECT_EQ(t.num_components, components);
}

/// lo < value < hi.
inline void expect_between(double value, double lo, double hi, const char* what) {
  EXPECT_GT(value, lo) << what;
  EXPECT_LT(value, hi) << what;
}

}  // namespace dresskit::test
