"""Input and output: datasets and their coordinates, provenance, tables, plotting, cache files."""
