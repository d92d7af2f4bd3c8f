"""Imported once by the ``forkserver`` process: load numpy, the harness, every plugin and every planner class.

Workers are forked from that server, so each starts with the plugins already
imported (and their numba functions loaded) instead of discovering them
again: replacing a killed worker costs a fork, not a second of imports.
Importing this module has that side effect on purpose; nothing else imports it.
"""

from pathzoo.harness.worker import preload_planners

preload_planners()
