/*
 * fx_guard.h — force-included (-include) into every fsw/ translation unit.
 * Poisons floating-point types and heap calls: any later use of these identifiers is a hard
 * compile error in flight code. It cannot see floating *literals* (e.g. `a > 0.5`), which GCC
 * folds into integer compares; tools/lint/scan_float.py catches those (spec 00 §4).
 */
#ifndef FSW_FX_GUARD_H
#define FSW_FX_GUARD_H
#pragma GCC poison float double malloc calloc realloc free
#endif
