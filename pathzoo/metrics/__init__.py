"""pathzoo.metrics."""
