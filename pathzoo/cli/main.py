"""Entry point of the ``pathzoo`` command: argument parsing and the one-line error contract.

Every :class:`~pathzoo.core.errors.PathzooError`, a missing or unreadable
file, a damaged database and Ctrl-C end the command with one line
``pathzoo: error: <message>`` on stderr and exit code 2, without a
traceback. Usage errors (argparse) also exit with code 2.
"""

from __future__ import annotations

import argparse
import difflib
import sqlite3
import sys
from typing import Sequence

from pathzoo.cli import (cmd_compare, cmd_completion, cmd_export, cmd_leaderboard, cmd_list, cmd_report,
                         cmd_reproduce, cmd_run, cmd_show, cmd_tune)
from pathzoo.core.errors import PathzooError

__all__ = ["build_parser", "main", "unknown_command", "EXIT_ERROR"]

EXIT_ERROR = 2
"""Exit code of every handled error, as for argparse usage errors."""


def build_parser() -> argparse.ArgumentParser:
    """The ``pathzoo`` parser with all subcommands."""
    from pathzoo import __version__

    parser = argparse.ArgumentParser(
        prog="pathzoo",
        description="Compare path planners honestly: run planners x scenarios x seeds, validate every path, "
        "and rank them with real statistics.",
        epilog="Run 'pathzoo COMMAND --help' for the options of a command.",
    )
    parser.add_argument("--version", action="version", version=f"pathzoo {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", required=True)
    for command in (cmd_list, cmd_run, cmd_tune, cmd_reproduce, cmd_leaderboard, cmd_report, cmd_export, cmd_show,
                    cmd_compare, cmd_completion):
        command.add_parser(sub)
    return parser


def unknown_command(parser: argparse.ArgumentParser, argv: Sequence[str]) -> str | None:
    """The error for a mistyped subcommand in ``argv``, with the closest command if one is near; else None."""
    if not argv or argv[0].startswith("-"):
        return None
    commands = next(a.choices for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    word = argv[0]
    if word in commands:
        return None
    close = difflib.get_close_matches(word, list(commands), n=1)
    hint = f"did you mean '{close[0]}'?" if close else f"choose one of {', '.join(commands)}"
    return f"unknown command '{word}'; {hint}"


def _one_line(exc: BaseException) -> str:
    if isinstance(exc, KeyboardInterrupt):
        return "interrupted"
    if isinstance(exc, OSError) and exc.filename is not None:
        return f"{exc.filename}: {exc.strerror or exc}"
    text = " ".join(str(exc).split())
    return text or type(exc).__name__


def main(argv: Sequence[str] | None = None) -> int:
    """Run the ``pathzoo`` command and return its exit code.

    Parameters
    ----------
    argv : sequence of str, optional
        Arguments without the program name (default: ``sys.argv[1:]``).
    """
    try:
        parser = build_parser()
        argv = sys.argv[1:] if argv is None else list(argv)
        mistyped = unknown_command(parser, argv)
        if mistyped is not None:
            print(f"pathzoo: error: {mistyped}", file=sys.stderr)
            return EXIT_ERROR
        try:
            args = parser.parse_args(argv)
        except SystemExit as exc:  # --help, --version and usage errors
            return int(exc.code or 0)
        return int(args.handler(args))
    except (PathzooError, OSError, sqlite3.Error, KeyboardInterrupt) as exc:
        print(f"pathzoo: error: {_one_line(exc)}", file=sys.stderr)
        return EXIT_ERROR


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
