/* limits.h — minimal ILP32 stub for static analysis only (see stdint.h in this directory,
   which also explains the (-(MAX) - 1) form of the minimum values). */
#ifndef LINT_LIMITS_H
#define LINT_LIMITS_H
#define CHAR_BIT   8
#define SCHAR_MIN  (-(127) - 1)
#define SCHAR_MAX  127
#define UCHAR_MAX  255
#define CHAR_MIN   SCHAR_MIN
#define CHAR_MAX   SCHAR_MAX
#define MB_LEN_MAX 16
#define SHRT_MIN   (-(32767) - 1)
#define SHRT_MAX   32767
#define USHRT_MAX  65535
#define INT_MIN    (-(2147483647) - 1)
#define INT_MAX    2147483647
#define UINT_MAX   4294967295U
#define LONG_MIN   (-(2147483647L) - 1L)
#define LONG_MAX   2147483647L
#define ULONG_MAX  4294967295UL
#define LLONG_MIN  (-(9223372036854775807LL) - 1LL)
#define LLONG_MAX  9223372036854775807LL
#define ULLONG_MAX 18446744073709551615ULL
#endif /* LINT_LIMITS_H */
