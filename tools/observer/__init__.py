"""Observer design and paper-reproduction tool (spec 10-observer §2-§4)."""
