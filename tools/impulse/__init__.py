"""Impulse scheduler tools (spec 50-impulse): CW model, double Newton solver, paper reproduction,
C table generator. Double precision only; golden values come from here or from the Eigen
reference (sim/impulse/imp_ref_*), never from the fixed-point code."""
