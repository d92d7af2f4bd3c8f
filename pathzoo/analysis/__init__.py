"""pathzoo.analysis."""
