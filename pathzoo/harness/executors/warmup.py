"""Imported once by the ``forkserver`` process: load numpy, the harness, every plugin and every planner class.

Workers are forked from that server, so each starts with the plugins already
imported (and their numba functions loaded) instead of discovering them
again: replacing a killed worker costs a fork, not a second of imports.

The server exits when the harness does: killed by the kernel
(:func:`~pathzoo.harness.launch.die_with_parent`, Linux, even in the middle
of these imports) or on end of file on its life pipe. It then skips the
interpreter's clean-up (``os._exit`` as the first exit handler): tearing down numba and every plugin takes seconds of CPU on a
loaded machine, and the workers it forked die only once it is gone
(:func:`pathzoo.harness.launch.die_with_harness`). Workers never run exit
handlers (a forkserver child always leaves through ``os._exit``).

Importing this module has these side effects on purpose; nothing else imports it.
"""

import atexit
import os

from pathzoo.harness.launch import die_with_parent

die_with_parent()  # the harness may be gone before the imports below end: the server's loop would notice only then

from pathzoo.harness.worker import preload_planners  # noqa: E402

preload_planners()
atexit.register(os._exit, 0)
