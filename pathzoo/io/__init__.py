"""Reading scenarios from files: scenario TOML, MovingAI maps and scenarios, occupancy arrays and DEMs."""
