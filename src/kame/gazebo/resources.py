"""Where a world's files come from: model:// on GAZEBO_MODEL_PATH (then kame's shipped models),
package:// through the package finder the caller passes in (the ROS side gives rospack's), file://,
and paths relative to the file that names them.

Pure: the model path and the finder are given; nothing here reads the environment.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path

from kame.gazebo.errors import GazeboError
from kame.gazebo.xmltree import Element, parse

SHIPPED_RESOURCES = str(Path(__file__).resolve().parent)  # its worlds/ folder, as Gazebo's share/gazebo-11
SHIPPED_MODELS = str(Path(__file__).resolve().parent / "models")


@dataclass(frozen=True)
class Resources:
    model_path: tuple[str, ...] = ()  # GAZEBO_MODEL_PATH's folders, searched before the shipped models
    find_package: Callable[[str], str | None] | None = None
    resource_path: tuple[str, ...] = ()  # GAZEBO_RESOURCE_PATH's folders, searched before kame's for worlds

    @staticmethod
    def from_environment(environ: Mapping[str, str], find_package: Callable[[str], str | None] | None = None,
                         extra_model_paths: tuple[str, ...] = ()) -> Resources:
        """GAZEBO_MODEL_PATH's folders (colon-separated, as Gazebo reads it), then `extra_model_paths`
        (the gazebo_model_path exports of packages, which the ROS side collects)."""
        paths = tuple(p for p in environ.get("GAZEBO_MODEL_PATH", "").split(os.pathsep) if p)
        resources = tuple(p for p in environ.get("GAZEBO_RESOURCE_PATH", "").split(os.pathsep) if p)
        return Resources(paths + extra_model_paths, find_package, resources)

    def world_file(self, name: str) -> str:
        """The world file `name` names, as gzserver finds it: a path that exists, else relative to
        GAZEBO_RESOURCE_PATH's folders, then kame's (so "worlds/empty.world" is kame's empty world)."""
        if os.path.isfile(name):
            return name
        for folder in (*self.resource_path, SHIPPED_RESOURCES):
            candidate = os.path.join(folder, name)
            if os.path.isfile(candidate):
                return candidate
        searched = ":".join(self.resource_path) or "(empty)"
        raise GazeboError(f"world file {name} not found, nor in GAZEBO_RESOURCE_PATH ({searched}) and kame's worlds")

    def model_folder(self, name: str, where: Element) -> str:
        for folder in (*self.model_path, SHIPPED_MODELS):
            candidate = os.path.join(folder, name)
            if os.path.isdir(candidate):
                return candidate
        searched = ":".join(self.model_path) or "(empty)"
        raise GazeboError(f"{where.where()}: model://{name} not found in GAZEBO_MODEL_PATH ({searched}) "
                          f"nor in kame's shipped models")

    def path(self, uri: str, where: Element) -> str:
        """The file or folder `uri` names."""
        uri = uri.strip()
        if uri.startswith("model://"):
            name, _, rest = uri[len("model://"):].partition("/")
            folder = self.model_folder(name, where)
            return os.path.join(folder, rest) if rest else folder
        if uri.startswith("package://"):
            package, _, rest = uri[len("package://"):].partition("/")
            found = self.find_package(package) if self.find_package is not None else None
            if not found:
                raise GazeboError(f"{where.where()}: package [{package}] not found for {uri}")
            return os.path.join(found, rest)
        if uri.startswith("file://"):
            return uri[len("file://"):]
        if os.path.isabs(uri):
            return uri
        if where.source.startswith("<"):
            raise GazeboError(f"{where.where()}: relative uri {uri!r} in text that is not from a file")
        return os.path.join(os.path.dirname(where.source), uri)

    def model_file(self, folder: str, where: Element) -> str:
        """The SDF file of a model folder: model.config's <sdf> (the newest version listed), else model.sdf."""
        config = os.path.join(folder, "model.config")
        if os.path.isfile(config):
            root = read_xml(config)
            listed = [(e.attrs.get("version", "0"), e.text.strip()) for e in root.each("sdf") if e.text.strip()]
            if listed:
                newest = max(listed, key=lambda pair: tuple(_version(pair[0])))
                return os.path.join(folder, newest[1])
        fallback = os.path.join(folder, "model.sdf")
        if os.path.isfile(fallback):
            return fallback
        raise GazeboError(f"{where.where()}: model folder {folder} has neither a model.config naming its SDF "
                          f"nor a model.sdf")


def _version(text: str) -> list[int]:
    return [int(part) if part.isdigit() else 0 for part in text.split(".")]


def read_xml(path: str) -> Element:
    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError as exc:
        raise GazeboError(f"cannot read {path}: {exc.strerror or exc}") from None
    return parse(data, path)
