"""Metaheuristic baselines: PSO (pyswarms), GA (DEAP), cuckoo search and fuzzy-GA."""
