"""Critical-difference diagram of mean Friedman ranks (Demšar 2006), drawn by scikit-posthocs."""

from __future__ import annotations

from typing import Any, Mapping

from matplotlib.axes import Axes

from pathzoo.analysis.ranks import FriedmanResult
from pathzoo.plotting.figure import new_axes, palette_for

__all__ = ["plot_cd_diagram"]


def plot_cd_diagram(result: FriedmanResult, ax: Axes | None = None, *,
                    palette: Mapping[str, Any] | None = None) -> Axes:
    """Draw mean ranks on a rank axis, with bars joining configurations the Nemenyi test cannot tell apart.

    :func:`scikit_posthocs.critical_difference_diagram` draws the diagram
    from the mean ranks and the pairwise Nemenyi p-values
    (:meth:`FriedmanResult.nemenyi_pvalues`); the critical difference is drawn
    above the axis. The best ranks are on the left. The title gives the
    Friedman p-value, since the post-hoc test is only meaningful once the
    Friedman test rejects.

    Parameters
    ----------
    result : FriedmanResult
        From :func:`pathzoo.analysis.ranks.friedman`.
    ax : Axes, optional
        Where to draw.
    palette : mapping, optional
        Colour per configuration (default: :func:`~pathzoo.plotting.figure.planner_colors`).
    """
    import scikit_posthocs as sp

    names = list(result.mean_ranks.index)
    ax = new_axes(ax, (7.0, 1.6 + 0.28 * len(names)))
    colors = palette_for(names, palette)
    sp.critical_difference_diagram(
        result.mean_ranks, result.nemenyi_pvalues(), cd=result.cd, alpha=result.alpha, ax=ax,
        color_palette={n: colors[n] for n in names}, label_fmt_left="{label} ({rank:.2f})",
        label_fmt_right="({rank:.2f}) {label}", label_props={"fontsize": "small"},
    )
    ax.set_title(
        f"{result.metric}: mean ranks over {result.n_scenarios} scenarios "
        f"(Friedman p = {result.pvalue:.3g}, Nemenyi α = {result.alpha:g})",
        fontsize="medium",
    )
    return ax
