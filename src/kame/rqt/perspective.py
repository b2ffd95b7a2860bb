"""The rqt window's plugins and its perspective (which plugins are docked, where, and the window's
geometry), as pure data and JSON text.

Rules:
- PLUGINS is the Plugins menu, grouped as rqt groups them; a plugin is named by its package
  (`rqt_plot` or `plot`), by rqt's plugin name (`rqt_plot/Plot`) or by its title (`Plot`),
  case-insensitively.
- Each docked instance is `<plugin>#<n>`, n counting from 1 per plugin; that key names its dock
  in the window's saved state, so the dock comes back where it was.
- The window's geometry and dock state are Qt's own (saveGeometry/saveState), kept as base64
  text; each instance keeps a small dict of its own settings (rqt_plot: its series).
- The file is `<ROS_HOME>/kame/rqt_gui.json` (ROS_HOME defaulting to ~/.ros), kame's own: rqt's
  `~/.config/ros.org/rqt_gui.ini` holds Python plugin classes kame does not have.
"""

from __future__ import annotations

import json
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

FORMAT = "kame-rqt-perspective/1"


class PerspectiveError(ValueError):
    """A plugin name that names no plugin, or a perspective file that is not one."""


@dataclass(frozen=True)
class PluginInfo:
    id: str  # the ROS package: rqt_graph
    group: str  # the Plugins submenu: Introspection
    title: str  # the menu entry and dock title: Node Graph
    rqt_name: str  # rqt's plugin name: rqt_graph/RosGraph

    def names(self) -> set[str]:
        return {self.id.lower(), self.title.lower(), self.rqt_name.lower(), self.id.removeprefix("rqt_").lower()}


PLUGINS = (
    PluginInfo("rqt_graph", "Introspection", "Node Graph", "rqt_graph/RosGraph"),
    PluginInfo("rqt_console", "Logging", "Console", "rqt_console/Console"),
    PluginInfo("rqt_logger_level", "Logging", "Logger Level", "rqt_logger_level/LoggerLevel"),
    PluginInfo("rqt_plot", "Visualization", "Plot", "rqt_plot/Plot"),
    PluginInfo("rqt_image_view", "Visualization", "Image View", "rqt_image_view/ImageView"),
    PluginInfo("rqt_topic", "Topics", "Topic Monitor", "rqt_topic/TopicPlugin"),
    PluginInfo("rqt_publisher", "Topics", "Message Publisher", "rqt_publisher/Publisher"),
    PluginInfo("rqt_service_caller", "Services", "Service Caller", "rqt_service_caller/ServiceCaller"),
    PluginInfo("rqt_reconfigure", "Configuration", "Dynamic Reconfigure", "rqt_reconfigure/Param"),
)


def find_plugin(name: str, plugins: Iterable[PluginInfo] = PLUGINS) -> PluginInfo:
    wanted = name.strip().lower()
    known = list(plugins)
    for plugin in known:
        if wanted in plugin.names():
            return plugin
    raise PerspectiveError(f"no plugin named {name!r}; there are: {', '.join(p.id for p in known)}")


def menu(plugins: Iterable[PluginInfo] = PLUGINS) -> dict[str, list[PluginInfo]]:
    """The Plugins menu: group -> its plugins, groups and entries in alphabetical order."""
    groups: dict[str, list[PluginInfo]] = {}
    for plugin in plugins:
        groups.setdefault(plugin.group, []).append(plugin)
    return {group: sorted(entries, key=lambda p: p.title) for group, entries in sorted(groups.items())}


@dataclass(frozen=True)
class DockedPlugin:
    plugin: str  # PluginInfo.id
    instance: int
    settings: Mapping[str, Any] = field(default_factory=dict)

    @property
    def key(self) -> str:
        return f"{self.plugin}#{self.instance}"


def dock_title(info: PluginInfo, instance: int) -> str:
    return info.title if instance == 1 else f"{info.title} ({instance})"


def next_instance(docked: Iterable[DockedPlugin], plugin: str) -> int:
    """The lowest instance number not in use for `plugin`."""
    used = {d.instance for d in docked if d.plugin == plugin}
    number = 1
    while number in used:
        number += 1
    return number


@dataclass(frozen=True)
class Perspective:
    plugins: tuple[DockedPlugin, ...] = ()
    geometry: str = ""  # base64 of QMainWindow.saveGeometry()
    state: str = ""  # base64 of QMainWindow.saveState(): where each dock is


def dumps(perspective: Perspective) -> str:
    return json.dumps({
        "format": FORMAT,
        "plugins": [{"plugin": d.plugin, "instance": d.instance, "settings": dict(d.settings)}
                    for d in perspective.plugins],
        "geometry": perspective.geometry,
        "state": perspective.state,
    }, indent=2) + "\n"


def loads(text: str, plugins: Iterable[PluginInfo] = PLUGINS) -> Perspective:
    """A perspective from dumps' text; a plugin this kame does not have is an error, not dropped."""
    try:
        data = json.loads(text)
    except json.JSONDecodeError as exc:
        raise PerspectiveError(f"not a perspective (JSON): {exc}") from exc
    if not isinstance(data, dict) or data.get("format") != FORMAT:
        raise PerspectiveError(f"not a perspective: no \"format\": \"{FORMAT}\"")
    known = {p.id for p in plugins}
    docked = []
    for entry in data.get("plugins", []):
        if not isinstance(entry, dict) or not isinstance(entry.get("plugin"), str) or \
                not isinstance(entry.get("instance"), int) or not isinstance(entry.get("settings", {}), dict):
            raise PerspectiveError(f"not a plugin entry: {entry!r}")
        if entry["plugin"] not in known:
            raise PerspectiveError(f"unknown plugin {entry['plugin']!r}")
        docked.append(DockedPlugin(entry["plugin"], entry["instance"], entry.get("settings", {})))
    keys = [d.key for d in docked]
    if len(set(keys)) != len(keys):
        raise PerspectiveError("a plugin instance is listed twice")
    return Perspective(tuple(docked), str(data.get("geometry", "")), str(data.get("state", "")))


def perspective_path(env: Mapping[str, str], home: Path) -> Path:
    """Where the rqt window keeps its perspective between runs."""
    ros_home = env.get("ROS_HOME") or str(home / ".ros")
    return Path(ros_home) / "kame" / "rqt_gui.json"
