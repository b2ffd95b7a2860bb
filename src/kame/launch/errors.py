"""The launch package's errors: one class, with the file and line it is about when known."""

from __future__ import annotations


class LaunchError(Exception):
    """A launch file that cannot be loaded or run (roslaunch's RLException), nothing started.

    `str()` is roslaunch's own wording; `where` (file:line) is added by `describe()`.
    """

    def __init__(self, message: str, filename: str | None = None, line: int | None = None) -> None:
        super().__init__(message)
        self.message = message
        self.filename = filename
        self.line = line

    def __str__(self) -> str:
        return self.message

    @property
    def where(self) -> str | None:
        if self.filename is None:
            return None
        return f"{self.filename}:{self.line}" if self.line is not None else self.filename

    def describe(self) -> str:
        """The message, then where it happened on a line of its own."""
        where = self.where
        return self.message if where is None else f"{self.message}\n  at {where}"


class ArgError(LaunchError):
    """`$(arg name)` of an arg with no value: the message is the arg's name, as roslaunch's."""


class PackageNotFound(LaunchError):
    """`$(find pkg)` or `<node pkg>` of an unknown package: the name, then `ROS path [i]=...` lines."""
