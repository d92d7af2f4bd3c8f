"""Rivals from the papers' comparison tables that are not ant colonies (GGACO's Table 2)."""
