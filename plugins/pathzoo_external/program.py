"""What an external planner is on disk: its command or function file, and a digest of the files that define it."""

from __future__ import annotations

import hashlib
from dataclasses import dataclass
from pathlib import Path

from pathzoo.core.errors import ExternalPlannerError

__all__ = ["Program", "PROTOCOL_VERSION", "SHIM_DIR"]

PROTOCOL_VERSION = 1
"""The protocol version sent in every problem (``problem.protocol``)."""

SHIM_DIR = Path(__file__).resolve().parent / "octave"
"""The Octave files that serve requests in a worker's Octave process."""


@dataclass(frozen=True)
class Program:
    """A command (``command``) or an Octave function file (``octave``), as given by its declaration.

    The planner's ``version`` is :meth:`digest`: a change to the program's
    files changes the run keys, so results of an edited program never mix
    with the old ones.
    """

    command: tuple[str, ...] = ()
    octave: str = ""

    def files(self) -> list[Path]:
        """The files whose contents define the planner.

        For a command, every argument that is an absolute path of a file;
        for an Octave function, every ``.m`` file of its folder (all are on
        Octave's path while it runs) and of pathzoo's shim.
        """
        if self.octave:
            folder = Path(self.octave).parent
            return sorted(folder.glob("*.m")) + sorted(SHIM_DIR.glob("*.m"))
        return [Path(arg) for arg in self.command if Path(arg).is_absolute() and Path(arg).is_file()]

    def digest(self) -> str:
        """12 hex digits of SHA-256 over the protocol version, the command or file name, and the files' contents."""
        h = hashlib.sha256(f"protocol {PROTOCOL_VERSION}\0{self.command!r}\0{self.octave}\0".encode())
        for path in self.files():
            try:
                data = path.read_bytes()
            except OSError:
                data = b"(unreadable)"
            h.update(f"{path}\0{len(data)}\0".encode())
            h.update(data)
        return h.hexdigest()[:12]

    def check_unchanged(self, planner_id: str, version: str) -> None:
        """Raise if the files changed since the planner's version was taken (an edit during an experiment).

        Raises
        ------
        ExternalPlannerError
            Naming the planner.
        """
        if self.digest() != version:
            raise ExternalPlannerError(
                f"{planner_id}: its files changed since the experiment was read (version {version}); "
                "read the experiment again to run the new version")
