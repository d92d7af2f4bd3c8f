"""Experiment files shipped with pathzoo (``default.toml`` is what ``pathzoo run`` runs)."""
