"""Benchmarks (README.md here): fx_insn (instruction counts on the emulated Cortex-M) and provenance
(machine and commit of a report)."""
