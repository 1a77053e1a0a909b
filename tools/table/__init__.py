"""Parameter-table image writer (image_writer) and the loader's test-image oracle (mktable)."""
