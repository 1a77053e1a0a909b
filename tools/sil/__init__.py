"""SIL log tools, the same for every mission (spec 00 §5): LCM log reading (lcmio), the run report's
dispatch and shared figures (report; each mission's own part is tools/<module>/report.py), the
report/summary agreement check (agree) and log comparison (compare). Names and telemetry layouts
come from tools.iface; nothing here names a mission."""
