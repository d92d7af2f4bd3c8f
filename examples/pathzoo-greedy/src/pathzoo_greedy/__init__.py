"""pathzoo-greedy: an example third-party pathzoo plugin providing ``greedy.best_first``."""

from pathzoo_greedy.planner import GreedyBestFirst

__all__ = ["GreedyBestFirst"]
