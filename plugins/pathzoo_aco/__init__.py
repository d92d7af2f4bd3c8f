"""Ant-colony planners: one shared engine, the classic ant systems and the five papers' variants."""
