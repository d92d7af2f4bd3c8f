"""The bridge to external planners: commands speaking pathzoo's JSON protocol, and Octave/MATLAB function files.

See ``docs/external-planners.md``. The planner classes are built from
declarations (:class:`pathzoo.plugins.external.ExternalPlanner`) by
:func:`pathzoo_external.declared.planner_class`.
"""
