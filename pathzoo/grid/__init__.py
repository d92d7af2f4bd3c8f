"""Shared grid machinery: neighbourhood graphs, segment tests, terrain geometry and clearance."""
