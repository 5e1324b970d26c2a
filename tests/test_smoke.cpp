#include <gtest/gtest.h>

#include "fixed_point.h"

TEST(Smoke, Builds) { EXPECT_EQ(glint::uq(1, 15).raw_one(), 32768); }
