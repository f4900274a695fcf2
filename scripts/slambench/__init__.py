"""The SLAM benchmark's parts (scripts/slam_benchmark.py; docs/slam.md)."""
