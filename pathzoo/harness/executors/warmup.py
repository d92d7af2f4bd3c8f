"""Imported once by the ``forkserver`` process: what every harness process needs, and no plugin at all.

The workers *and* the judge are forked from that server
(:mod:`pathzoo.harness.launch`), so what it does here is paid once instead
of once in each of them: numpy, numba, the parts of scipy the harness uses,
pathzoo's geometry, rules, validators and built-in metrics, the harness's
own modules, and numba's start-up with the shared geometry kernels (the
neighbourhood graph, clearance and digest of the tiny ``grid2d`` map of
:mod:`pathzoo.core.tiny_scenarios`, loaded from numba's cache or compiled). It never discovers
plugins and never imports a planner or a scenario plugin: the judge must
start in a process where no planner code ran, and import its scenario and
metric plugins itself (``docs/register-a-planner.md``). Each worker
discovers the plugins and imports the planner classes it runs.

The server exits when the harness does: killed by the kernel
(:func:`~pathzoo.harness.launch.die_with_parent`, Linux, even in the middle
of these imports) or on end of file on its life pipe. It then skips the
interpreter's clean-up (``os._exit`` as the first exit handler): tearing
down numba takes a while on a loaded machine, and the processes it forked
die only once it is gone (:func:`pathzoo.harness.launch.die_with_harness`).
Its children never run exit handlers (a forkserver child always leaves
through ``os._exit``).

The worker's own loop (:mod:`pathzoo.harness.executors.worker_loop`) is the
server's next preload (:data:`pathzoo.harness.launch.PRELOAD`), not an
import of this module: a sandboxed worker, spawned rather than forked,
imports this module from inside that code.

Importing this module has these side effects on purpose.
"""

import atexit
import os

from pathzoo.harness.launch import die_with_parent

die_with_parent()  # the harness may be gone before the imports below end: the server's loop would notice only then

import pathzoo.harness.judge_worker  # noqa: E402,F401 - the judge's code
import pathzoo.metrics.catalogue  # noqa: E402,F401 - the built-in metrics the judge computes (every metric module)
from pathzoo.harness.digest import scenario_digest, warm  # noqa: E402
from pathzoo.core.tiny_scenarios import check_scenario  # noqa: E402
from pathzoo.core.warmup import warm_up  # noqa: E402,F401 - every worker's untimed first call

scenario_digest(warm(check_scenario("grid2d")))
atexit.register(os._exit, 0)
