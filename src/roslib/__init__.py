"""roslib, for the old tutorials' first lines (`import roslib; roslib.load_manifest('pkg')`)."""

from roslib.launcher import load_manifest

__all__ = ["is_interactive", "load_manifest", "set_interactive"]

_is_interactive = False


def set_interactive(interactive: bool) -> None:
    """Say whether the script runs interactively (libraries may then not exit on errors)."""
    global _is_interactive
    _is_interactive = interactive


def is_interactive() -> bool:
    return _is_interactive
