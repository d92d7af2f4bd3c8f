"""Exact reference planners: Dijkstra, A* and Theta*."""
