// imp_ref_detail — small helpers shared by the parts of the impulse double reference
// (imp_ref_solver, imp_ref_checks, imp_ref_fsw). Internal to sim/impulse: callers include the
// part they use, never this header.
#pragma once

namespace ref {
namespace detail {

// Subsystems of the solve: 0 = coupled x-y (2 axes from axis 0, state rows 0..3), 1 = z (1 axis,
// axis 2, rows 4..5).
inline int sub_nax(int sub) { return sub == 0 ? 2 : 1; }
inline int sub_ax0(int sub) { return sub == 0 ? 0 : 2; }
inline int sub_row0(int sub) { return sub == 0 ? 0 : 4; }

// Scales of the flight code's Q formats (flight table values -> reference doubles).
inline constexpr double kQ28 = 268435456.0;
inline constexpr double kQ29 = 536870912.0;
inline constexpr double kQ30 = 1073741824.0;

}  // namespace detail
}  // namespace ref
