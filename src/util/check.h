// Invariant checks that print their operands (after pbrt-v4's CHECK macros): a failed
// WT_CHECK_LE(shadows, n) prints "kernels/wave.h:40: WT_CHECK_LE(shadows, n) failed: shadows =
// 70, n = 64" and aborts. WT_CHECK* are always on, for the cheap checks outside hot loops;
// WT_DCHECK* only where WAVETRACE_DCHECKS is defined (debug builds and the sanitized build of
// `make sanitize`), for the invariants of the kernels' inner loops, and compile to nothing
// else (their operands are still type-checked, never evaluated).
#pragma once

#include <sstream>
#include <string>

namespace wavetrace::check_detail {

[[noreturn]] void fail(const char* file, int line, const std::string& message);

template <class A, class B>
[[noreturn]] void fail_op(const char* file,
                          int line,
                          const char* check,
                          const char* a_text,
                          const char* b_text,
                          const A& a,
                          const B& b) {
    std::ostringstream s;
    s << check << "(" << a_text << ", " << b_text << ") failed: " << a_text << " = " << a << ", "
      << b_text << " = " << b;
    fail(file, line, s.str());
}

}  // namespace wavetrace::check_detail

#define WT_CHECK(x)                                                                         \
    do {                                                                                    \
        if (!(x)) [[unlikely]]                                                              \
            ::wavetrace::check_detail::fail(__FILE__, __LINE__, "WT_CHECK(" #x ") failed"); \
    } while (false)

#define WT_CHECK_OP_(name, op, a, b)                                                          \
    do {                                                                                      \
        const auto& wt_check_a_ = (a);                                                        \
        const auto& wt_check_b_ = (b);                                                        \
        if (!(wt_check_a_ op wt_check_b_)) [[unlikely]]                                       \
            ::wavetrace::check_detail::fail_op(__FILE__, __LINE__, name, #a, #b, wt_check_a_, \
                                               wt_check_b_);                                  \
    } while (false)

#define WT_CHECK_EQ(a, b) WT_CHECK_OP_("WT_CHECK_EQ", ==, a, b)
#define WT_CHECK_NE(a, b) WT_CHECK_OP_("WT_CHECK_NE", !=, a, b)
#define WT_CHECK_LT(a, b) WT_CHECK_OP_("WT_CHECK_LT", <, a, b)
#define WT_CHECK_LE(a, b) WT_CHECK_OP_("WT_CHECK_LE", <=, a, b)
#define WT_CHECK_GT(a, b) WT_CHECK_OP_("WT_CHECK_GT", >, a, b)
#define WT_CHECK_GE(a, b) WT_CHECK_OP_("WT_CHECK_GE", >=, a, b)

#ifdef WAVETRACE_DCHECKS
#define WT_DCHECK(x) WT_CHECK(x)
#define WT_DCHECK_EQ(a, b) WT_CHECK_EQ(a, b)
#define WT_DCHECK_NE(a, b) WT_CHECK_NE(a, b)
#define WT_DCHECK_LT(a, b) WT_CHECK_LT(a, b)
#define WT_DCHECK_LE(a, b) WT_CHECK_LE(a, b)
#define WT_DCHECK_GT(a, b) WT_CHECK_GT(a, b)
#define WT_DCHECK_GE(a, b) WT_CHECK_GE(a, b)
#else
// Never evaluated, but compiled: a DCHECK cannot rot in release builds.
#define WT_DCHECK(x)   \
    do {               \
        if (false) {   \
            (void)(x); \
        }              \
    } while (false)
#define WT_DCHECK_OP_(a, b) \
    do {                    \
        if (false) {        \
            (void)(a);      \
            (void)(b);      \
        }                   \
    } while (false)
#define WT_DCHECK_EQ(a, b) WT_DCHECK_OP_(a, b)
#define WT_DCHECK_NE(a, b) WT_DCHECK_OP_(a, b)
#define WT_DCHECK_LT(a, b) WT_DCHECK_OP_(a, b)
#define WT_DCHECK_LE(a, b) WT_DCHECK_OP_(a, b)
#define WT_DCHECK_GT(a, b) WT_DCHECK_OP_(a, b)
#define WT_DCHECK_GE(a, b) WT_DCHECK_OP_(a, b)
#endif
