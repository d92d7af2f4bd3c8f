"""The ``pathzoo`` command line: list plugins, run experiments, print leaderboards, draw scenarios.

Each subcommand lives in its own module exposing ``add_parser(subparsers)``;
:mod:`pathzoo.cli.main` wires them together and turns pathzoo's errors into
one-line messages with exit code 2 (see ``docs/cli.md``).
"""
