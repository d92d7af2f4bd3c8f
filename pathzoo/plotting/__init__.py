"""Figures for scenarios and results, drawn with matplotlib's object API on the Agg canvas.

No function here imports ``matplotlib.pyplot`` or calls ``show()``: each
builds a :class:`matplotlib.figure.Figure` (or draws on the ``ax`` it is
given) and returns the Axes, so plotting works headless, in worker processes
and in notebooks alike. Save with ``ax.figure.savefig(...)`` or
:func:`pathzoo.plotting.figure.save_figure`.
"""
