"""pathzoo.testing."""
