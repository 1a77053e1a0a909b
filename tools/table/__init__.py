"""Parameter-table image writer (image_writer, with the flight loaders' limits), the loader's test-image oracle
(mktable) and mission configuration files (config: YAML + pydantic schema, clear errors)."""
