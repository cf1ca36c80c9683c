"""Input and output: configuration, datasets and their coordinates, provenance, code fingerprints, tables, plotting, archive, cache files."""
