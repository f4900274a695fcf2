"""Rendered SLAM sequences with exact ground truth (scripts/make_sequences.py; docs/slam.md)."""
