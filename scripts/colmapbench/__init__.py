"""The COLMAP benchmark's pieces (scripts/colmap_benchmark.py, docs/colmap.md)."""
