// Check macros for the C++ sim tests on top of CMocka. Like tests/common/ut.h, checks record and
// continue, and the test fails when its body has returned, so no longjmp skips a destructor.
#ifndef TESTS_SIM_SIM_TEST_HPP
#define TESTS_SIM_SIM_TEST_HPP

#include <cmath>
#include <cstdarg>
#include <cstddef>
#include <cstdint>
#include <csetjmp>
#include <cstdio>

extern "C" {
#include <cmocka.h>
}

namespace simtest {
inline unsigned &fails()
{
    static unsigned n = 0u;
    return n;
}
}  // namespace simtest

#define SIM_TEST(name)                                       \
    static void name##_body();                               \
    static void name(void **)                                \
    {                                                        \
        simtest::fails() = 0u;                               \
        name##_body();                                       \
        if (simtest::fails() != 0u) {                        \
            fail_msg("%u check(s) failed", simtest::fails()); \
        }                                                    \
    }                                                        \
    static void name##_body()

#define EXPECT_TRUE(c)                                                               \
    do {                                                                             \
        if (!(c)) {                                                                  \
            std::printf("%s:%d: check failed: %s\n", __FILE__, __LINE__, #c);        \
            ++simtest::fails();                                                      \
        }                                                                            \
    } while (0)

// |a - b| <= tol, NaN fails.
#define EXPECT_NEAR(a, b, tol)                                                                      \
    do {                                                                                            \
        const double sa_ = (a), sb_ = (b), st_ = (tol);                                             \
        if (!(std::fabs(sa_ - sb_) <= st_)) {                                                       \
            std::printf("%s:%d: |%s - %s| = %.3e > %.3e (%.15g vs %.15g)\n", __FILE__, __LINE__, #a, \
                        #b, std::fabs(sa_ - sb_), st_, sa_, sb_);                                   \
            ++simtest::fails();                                                                     \
        }                                                                                           \
    } while (0)

#define EXPECT_LE(a, b)                                                                                  \
    do {                                                                                                 \
        const double sa_ = (a), sb_ = (b);                                                               \
        if (!(sa_ <= sb_)) {                                                                             \
            std::printf("%s:%d: check failed: %s <= %s (%.6e vs %.6e)\n", __FILE__, __LINE__, #a, #b, sa_, \
                        sb_);                                                                            \
            ++simtest::fails();                                                                          \
        }                                                                                                \
    } while (0)

#define EXPECT_EQ_INT(a, b)                                                                            \
    do {                                                                                               \
        const long long sa_ = static_cast<long long>(a), sb_ = static_cast<long long>(b);              \
        if (sa_ != sb_) {                                                                              \
            std::printf("%s:%d: check failed: %s == %s (%lld vs %lld)\n", __FILE__, __LINE__, #a, #b, sa_, \
                        sb_);                                                                          \
            ++simtest::fails();                                                                        \
        }                                                                                              \
    } while (0)

#endif
