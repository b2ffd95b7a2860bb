"""rosmaster, importable: `rosmaster.master.Master(port).start()` runs kame's master in this
process (the `rosmaster` command is kame.cli.rosmaster)."""

from __future__ import annotations

from .master import DEFAULT_MASTER_PORT, NUM_WORKERS, Master

__all__ = ["DEFAULT_MASTER_PORT", "NUM_WORKERS", "Master"]
