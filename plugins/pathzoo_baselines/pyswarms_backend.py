"""pyswarms' backend, imported without letting pyswarms reconfigure the process's logging.

Importing pyswarms (and building its topologies and handlers) creates
``Reporter`` objects whose set-up calls :func:`logging.config.dictConfig`
with pyswarms' defaults: it replaces the root logger's handlers, sets it to
INFO and opens ``report.log`` in the current directory. A library planner must
not do that to the harness or to a user's program, so this module imports the
backend with ``dictConfig`` disabled and turns the reporters' set-up into a
no-op for later objects. Only the names ``swarm.pso`` uses are re-exported.
"""

from __future__ import annotations

import logging.config
import threading

__all__ = ["BoundaryHandler", "Star", "VelocityHandler", "compute_pbest", "create_swarm"]

_lock = threading.Lock()

with _lock:
    _dict_config = logging.config.dictConfig
    logging.config.dictConfig = lambda config: None
    try:
        from pyswarms.backend.generators import create_swarm
        from pyswarms.backend.handlers import BoundaryHandler, VelocityHandler
        from pyswarms.backend.operators import compute_pbest
        from pyswarms.backend.topology import Star
        from pyswarms.utils.reporter.reporter import Reporter
    finally:
        logging.config.dictConfig = _dict_config
    Reporter._setup_logger = lambda self, path=None: None
