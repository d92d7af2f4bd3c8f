"""OMPL sampling-based planners through the ompl 2.x nanobind bindings."""
