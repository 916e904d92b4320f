// WT_CHECK and WT_DCHECK (src/util/check.h): a failed check names the expression and its
// operands' values, then aborts; a DCHECK costs nothing where DCHECKs are off.
#include <gtest/gtest.h>

#include "util/check.h"

namespace {

int checked_division(int a, int b) {
    WT_CHECK_NE(b, 0);
    return a / b;
}

}  // namespace

TEST(Check, PassingChecksDoNothing) {
    WT_CHECK(1 + 1 == 2);
    WT_CHECK_EQ(2, 2);
    WT_CHECK_LT(1, 2);
    WT_CHECK_LE(2, 2);
    WT_CHECK_GT(3, 2);
    WT_CHECK_GE(3, 3);
    EXPECT_EQ(checked_division(6, 3), 2);
}

TEST(CheckDeathTest, AFailedCheckPrintsTheOperandsAndAborts) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    const size_t shadows = 70, n = 64;
    EXPECT_DEATH(WT_CHECK_LE(shadows, n),
                 "WT_CHECK_LE\\(shadows, n\\) failed: shadows = 70, n = 64");
    EXPECT_DEATH(checked_division(1, 0), "WT_CHECK_NE\\(b, 0\\) failed: b = 0, 0 = 0");
    EXPECT_DEATH(WT_CHECK(n < 10), "test_check.cpp:[0-9]+: WT_CHECK\\(n < 10\\) failed");
}

// Each operand is evaluated once when DCHECKs are on, never when they are off.
TEST(Check, DchecksEvaluateTheirOperandsOnlyWhenOn) {
    int calls = 0;
    WT_DCHECK(++calls > 0);
    WT_DCHECK_LE(++calls, 100);
#ifdef WAVETRACE_DCHECKS
    EXPECT_EQ(calls, 2);
#else
    EXPECT_EQ(calls, 0);
#endif
}
