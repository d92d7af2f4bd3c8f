"""Jinja2 templates of the HTML outputs (tables, the experiment report), with autoescaping on."""

from __future__ import annotations

from functools import lru_cache

import jinja2

__all__ = ["environment"]


@lru_cache(maxsize=1)
def environment() -> jinja2.Environment:
    """The template environment: templates from this package, HTML autoescaping, strict undefined names."""
    return jinja2.Environment(
        loader=jinja2.PackageLoader("pathzoo.analysis", "templates"),
        autoescape=jinja2.select_autoescape(default=True, default_for_string=True),
        undefined=jinja2.StrictUndefined,
        trim_blocks=True,
        lstrip_blocks=True,
        keep_trailing_newline=True,
    )
