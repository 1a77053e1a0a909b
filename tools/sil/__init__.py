"""SIL log analysis: telemetry decoding, run reports and log comparison (spec 00 §5, 10-observer §6-§7)."""
