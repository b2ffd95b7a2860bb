"""A Gazebo plugin's parameters: the children of its <plugin> element, read as gazebo_ros's
plugins read them, without I/O.

A missing parameter takes the plugin's default and leaves one line saying so, in the words of
the plugin it stands for (`missing`, a format with {tag} and {default}); a value that is not a
number where one is needed is an error the caller reports before the plugin starts.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from kame.gazebo.description import Plugin

# GazeboRos::getParameter's line (gazebo_plugins' gazebo_ros_utils), which the drives print
GAZEBO_ROS_MISSING = "{info}: missing <{tag}> default is {default}"


class PluginParameterError(ValueError):
    """A plugin parameter the plugin cannot start with; the text names the plugin and the tag."""


def _shown(value: object) -> str:
    if isinstance(value, bool):
        return "1" if value else "0"  # boost::lexical_cast<std::string>(bool), as gazebo_ros prints it
    if isinstance(value, float) and value == int(value):
        return str(int(value))
    return str(value)


class Parameters:
    """Typed reads of one plugin's parameters; `notes` collects the missing-parameter lines."""

    def __init__(self, plugin: Plugin, info: str, missing: str = GAZEBO_ROS_MISSING) -> None:
        self.plugin = plugin
        self.info = info
        self._missing = missing
        self._values = plugin.parameters()
        self.notes: list[str] = []

    def has(self, tag: str) -> bool:
        return tag in self._values

    def _absent(self, tag: str, default: object) -> None:
        self.notes.append(self._missing.format(info=self.info, tag=tag, default=_shown(default)))

    def text(self, tag: str, default: str, quiet: bool = False) -> str:
        if tag not in self._values:
            if not quiet:
                self._absent(tag, default)
            return default
        return self._values[tag]

    def number(self, tag: str, default: float, quiet: bool = False) -> float:
        if tag not in self._values:
            if not quiet:
                self._absent(tag, default)
            return default
        raw = self._values[tag]
        try:
            value = float(raw)
        except ValueError:
            raise PluginParameterError(f"{self.info}: <{tag}> must be a number, not {raw!r}") from None
        if not math.isfinite(value):
            raise PluginParameterError(f"{self.info}: <{tag}> must be a finite number, not {raw!r}")
        return value

    def whole(self, tag: str, default: int, quiet: bool = False) -> int:
        value = self.number(tag, default, quiet)
        if value != int(value):
            raise PluginParameterError(f"{self.info}: <{tag}> must be a whole number, not {value!r}")
        return int(value)

    def flag(self, tag: str, default: bool, quiet: bool = False) -> bool:
        if tag not in self._values:
            if not quiet:
                self._absent(tag, default)
            return default
        raw = self._values[tag].lower()
        if raw in ("true", "1"):
            return True
        if raw in ("false", "0"):
            return False
        raise PluginParameterError(f"{self.info}: <{tag}> must be true or false, not {self._values[tag]!r}")

    def vector(self, tag: str, default: Sequence[float], quiet: bool = False) -> tuple[float, ...]:
        if tag not in self._values:
            if not quiet:
                self._absent(tag, " ".join(_shown(float(v)) for v in default))
            return tuple(float(v) for v in default)
        raw = self._values[tag].split()
        try:
            values = tuple(float(v) for v in raw)
        except ValueError:
            raise PluginParameterError(f"{self.info}: <{tag}> must be {len(default)} numbers, "
                                       f"not {self._values[tag]!r}") from None
        if len(values) != len(default) or not all(math.isfinite(v) for v in values):
            raise PluginParameterError(f"{self.info}: <{tag}> must be {len(default)} finite numbers, "
                                       f"not {self._values[tag]!r}")
        return values

    def namespace(self) -> str:
        """<robotNamespace>, as gazebo_ros's plugins take it: "" when absent, without slashes around."""
        return self._values.get("robotNamespace", "").strip().strip("/")
