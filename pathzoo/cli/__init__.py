"""pathzoo.cli."""
