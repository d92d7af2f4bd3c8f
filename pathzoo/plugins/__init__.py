"""Plugin discovery (entry points + pluggy) and the registry of planners, scenarios and metrics."""
