"""Critical-difference diagram of mean Friedman ranks (Demšar 2006)."""

from __future__ import annotations

import math

from matplotlib.axes import Axes

from pathzoo.analysis.ranks import FriedmanResult
from pathzoo.plotting.figure import new_axes

__all__ = ["plot_cd_diagram"]


def plot_cd_diagram(result: FriedmanResult, ax: Axes | None = None) -> Axes:
    """Draw mean ranks on a rank axis, bars joining configurations within the critical difference.

    The best ranks are on the left. Configurations in the better half are
    labelled on the left, the others on the right; a thick bar joins every
    maximal group whose mean ranks differ by less than the Nemenyi CD (drawn
    above the axis). The title gives the Friedman p-value, since the CD is
    only meaningful once the Friedman test rejects.
    """
    k = result.n_configs
    names = list(result.mean_ranks.index)
    ranks = result.mean_ranks.to_numpy()
    cliques = result.cliques()
    n_left = math.ceil(k / 2)
    row = 0.32
    first = 0.35 + 0.14 * len(cliques)
    height = first + row * max(n_left, k - n_left)
    ax = new_axes(ax, (7.0, 1.3 + 0.9 * height))
    lo, hi = 1.0, float(max(k, 2))
    # rank axis with ticks
    ax.plot([lo, hi], [0, 0], color="black", lw=1.2)
    for t in range(1, int(hi) + 1):
        ax.plot([t, t], [0, -0.06], color="black", lw=1.0)
        ax.text(t, -0.1, str(t), ha="center", va="bottom", fontsize="small")
    # critical difference
    cd = result.cd
    y_cd = -0.42
    ax.plot([lo, lo + cd], [y_cd, y_cd], color="black", lw=1.5)
    for end in (lo, lo + cd):
        ax.plot([end, end], [y_cd - 0.04, y_cd + 0.04], color="black", lw=1.5)
    ax.text(lo + cd / 2, y_cd - 0.06, f"CD = {cd:.2f}", ha="center", va="bottom", fontsize="small")
    # configurations
    pad = 0.12 * (hi - lo) + 0.1
    for i, (name, r) in enumerate(zip(names, ranks)):
        if i < n_left:
            y, x_end, ha = first + row * i, lo - pad, "right"
        else:
            y, x_end, ha = first + row * (k - 1 - i), hi + pad, "left"
        ax.plot([r, r, x_end], [0, y, y], color="#333333", lw=1.0)
        ax.plot([r], [0], "o", color="#333333", ms=3)
        ax.text(x_end + (-0.05 if ha == "right" else 0.05), y, f"{name} ({r:.2f})", ha=ha, va="center",
                fontsize="small")
    # groups without significant differences
    for c, group in enumerate(cliques):
        rs = [ranks[names.index(g)] for g in group]
        y = 0.2 + 0.14 * c
        ax.plot([min(rs) - 0.03, max(rs) + 0.03], [y, y], color="black", lw=4, solid_capstyle="butt")
    ax.set_xlim(lo - pad - 0.05, hi + pad + 0.05)
    ax.set_ylim(height + 0.1, y_cd - 0.25)
    ax.axis("off")
    ax.set_title(
        f"{result.metric}: mean ranks over {result.n_scenarios} scenarios "
        f"(Friedman p = {result.pvalue:.3g}, Nemenyi α = {result.alpha:g})",
        fontsize="medium",
    )
    return ax
