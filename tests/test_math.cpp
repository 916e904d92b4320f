#include <gtest/gtest.h>

#include "wavetrace/wavetrace.h"

TEST(Math, Placeholder) { EXPECT_EQ(wavetrace::dot({1, 0, 0}, {0, 1, 0}), 0.0f); }
