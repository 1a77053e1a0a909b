/*
 * stdbool.h — minimal stub for static analysis only (see stdint.h in this directory).
 * `true` and `false` are deliberately NOT defined as 1 and 0: cppcheck knows them as boolean
 * constants, whereas the integer macros would make every `bool ok = true;` an essentially
 * signed value assigned to a boolean (a false MISRA 10.3).
 */
#ifndef LINT_STDBOOL_H
#define LINT_STDBOOL_H
#define bool _Bool
#define __bool_true_false_are_defined 1
#endif /* LINT_STDBOOL_H */
