"""Entry point of the ``pathzoo`` command: argument parsing and the one-line error contract.

Every :class:`~pathzoo.core.errors.PathzooError`, a missing or unreadable
file, a damaged database and Ctrl-C end the command with one line
``pathzoo: error: <message>`` on stderr and exit code 2, without a
traceback. Usage errors (argparse) are one line too, with exit code 2.
"""

from __future__ import annotations

import argparse
import sqlite3
import sys
from typing import Any, NoReturn, Sequence

from pathzoo.cli import (cmd_compare, cmd_completion, cmd_export, cmd_leaderboard, cmd_list, cmd_merge, cmd_report,
                         cmd_reproduce, cmd_run, cmd_show, cmd_tune)
from pathzoo.core.errors import PathzooError
from pathzoo.core.suggest import did_you_mean

__all__ = ["OneLineParser", "build_parser", "main", "unknown_command", "EXIT_ERROR"]

EXIT_ERROR = 2
"""Exit code of every handled error, as for argparse usage errors."""


class OneLineParser(argparse.ArgumentParser):
    """An argparse parser whose usage errors are one line, ``pathzoo: error: run: argument --jobs: ...``.

    argparse prints the usage block before the message; here the message
    names the subcommand and points to ``--help`` instead. A value outside an
    option's choices gets the closest choice as a suggestion. Subparsers are
    of the same class (argparse makes them of their parent's class).
    """

    def error(self, message: str) -> NoReturn:
        """Print one line and exit with :data:`EXIT_ERROR`."""
        command = self.prog.partition(" ")[2]
        where = f"{command}: " if command else ""
        text = " ".join(message.split())
        self.exit(EXIT_ERROR, f"pathzoo: error: {where}{text} (see '{self.prog} --help')\n")

    def _check_value(self, action: argparse.Action, value: Any) -> None:
        choices = action.choices
        if choices is not None and value not in choices:
            names = [str(c) for c in choices]
            hint = did_you_mean(str(value), names) or f"; choose from {', '.join(names)}"
            raise argparse.ArgumentError(action, f"invalid choice '{value}'{hint}")


def build_parser() -> argparse.ArgumentParser:
    """The ``pathzoo`` parser with all subcommands."""
    from pathzoo import __version__

    parser = OneLineParser(
        prog="pathzoo",
        description="Compare path planners honestly: run planners x scenarios x seeds, validate every path, "
        "and rank them with real statistics.",
        epilog="Run 'pathzoo COMMAND --help' for the options of a command.",
    )
    parser.add_argument("--version", action="version", version=f"pathzoo {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", required=True)
    for command in (cmd_list, cmd_run, cmd_tune, cmd_reproduce, cmd_leaderboard, cmd_report, cmd_export, cmd_show,
                    cmd_compare, cmd_merge, cmd_completion):
        command.add_parser(sub)
    parser.set_defaults(root_parser=parser)  # the completion command describes the whole parser
    return parser


def unknown_command(parser: argparse.ArgumentParser, argv: Sequence[str]) -> str | None:
    """The error for a mistyped subcommand in ``argv``, with the closest command if one is near; else None."""
    if not argv or argv[0].startswith("-"):
        return None
    commands = next(a.choices for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    word = argv[0]
    if word in commands:
        return None
    hint = did_you_mean(word, commands) or f"; choose one of {', '.join(commands)}"
    return f"unknown command '{word}'{hint}"


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
