/* stddef.h — minimal ILP32 stub for static analysis only (see stdint.h in this directory). */
#ifndef LINT_STDDEF_H
#define LINT_STDDEF_H
typedef unsigned int size_t;
typedef int          ptrdiff_t;
typedef long         wchar_t;
#define NULL ((void *)0)
#define offsetof(type, member) __builtin_offsetof(type, member)
#endif /* LINT_STDDEF_H */
