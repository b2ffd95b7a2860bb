"""Models entering and leaving the running world: SDF or URDF text spawned by kame.gazebo's World
(package:// and model:// found as gazebo_ros finds them: `resources_from`) at spawn_model's pose
under its name, their plugins started with the robot namespace the spawn request gives
(gazebo_ros writes it into every <plugin>), and stopped again on delete. The World refuses a
model spawned inside another, a malformed one or a missing mesh with a GazeboError saying why.
"""

from __future__ import annotations

import os
import xml.etree.ElementTree as ET
from collections.abc import Callable, Mapping
from dataclasses import replace
from pathlib import Path

from kame.catkin import executables
from kame.gazebo.errors import GazeboError
from kame.gazebo.poses import Pose
from kame.gazebo.resources import Resources
from kame.gazebo.sdf import SdfReader
from kame.gazebo.xmltree import parse
from kame.gazebo_ros.plugins import PluginHost
from kame.gazebo_ros.simulation import Simulation


class SpawnRefused(ValueError):
    """A spawn request gazebo_ros refuses; the text is its status message."""


def model_kind(text: str) -> str | None:
    """gazebo_ros's isURDF/isSDF: the document's root is <robot>, or <sdf> (or the old <gazebo>)."""
    try:
        root = ET.fromstring(text.strip())
    except ET.ParseError:
        return None
    if root.tag == "robot":
        return "urdf"
    if root.tag in ("sdf", "gazebo"):
        return "sdf"
    return None


def gazebo_model_paths(env: Mapping[str, str]) -> tuple[str, ...]:
    """The gazebo_model_path exports of the packages on ROS_PACKAGE_PATH (and kame's), as
    gazebo_ros's paths plugin adds them to GAZEBO_MODEL_PATH; ${prefix} is the package's folder."""
    found: list[str] = []
    for package in executables.packages(env).values():
        manifest = Path(package.path) / "package.xml"
        try:
            root = ET.parse(manifest).getroot()
        except (OSError, ET.ParseError):
            continue
        for export in root.iter("gazebo_ros"):
            path = export.get("gazebo_model_path")
            if path:
                found.append(path.replace("${prefix}", str(package.path)))
    return tuple(found)


def resources_from(env: Mapping[str, str]) -> Resources:
    packages = executables.packages(env)

    def find_package(name: str) -> str | None:
        package = packages.get(name)
        return str(package.path) if package is not None else None

    return Resources.from_environment(env, find_package, gazebo_model_paths(env))


class ModelFactory:
    """Spawns and deletes models in a Simulation and keeps their plugins; every call is made with
    the simulation's lock held."""

    def __init__(self, sim: Simulation, plugins: PluginHost, warn: Callable[[str], None]) -> None:
        self.sim = sim
        self.plugins = plugins
        self._warn = warn

    def spawn(self, text: str, name: str, pose: Pose, robot_namespace: str, kind: str) -> None:
        found = model_kind(text)
        if found is None:
            raise SpawnRefused("GazeboRosApiPlugin SpawnModel Failure: input model_xml not SDF or URDF, "
                               "or cannot be converted to Gazebo compatible format.")
        if found != kind:
            self._warn(f"SpawnModel: [{name}] was sent to spawn_{kind}_model but is {found.upper()}: "
                       f"spawned as {found.upper()}")
        world = self.sim.world
        if found == "urdf":
            world.spawn_urdf(text, name, pose, f"<{name}>")
        else:
            # gazebo_ros's updateSDFAttributes: the model's own <pose> is taken relative to the initial pose
            reader = SdfReader(world.resources)
            model = reader.model_document(parse(text, f"<{name}>"), name)
            for warning in reader.warnings:
                self._warn(warning)
            world.spawn(replace(model, pose=pose * model.pose))
        self.sim.report_warnings()
        self.plugins.start_model(world.model_description(name), robot_namespace.strip("/") if robot_namespace
                                 else None)

    def delete(self, name: str) -> None:
        self.plugins.stop_model(name)
        self.sim.world.delete_model(name)

    def reset_plugins(self) -> None:
        self.plugins.reset()


def world_file(name: str, env: Mapping[str, str], shipped: str) -> str:
    """The world file gzserver is given: a path as it stands, else on GAZEBO_RESOURCE_PATH (as
    "worlds/empty.world" is found), else among the worlds kame ships (`shipped`'s parent holds
    worlds/)."""
    if os.path.isfile(name):
        return name
    for folder in [*env.get("GAZEBO_RESOURCE_PATH", "").split(os.pathsep), shipped]:
        if folder and os.path.isfile(os.path.join(folder, name)):
            return os.path.join(folder, name)
    raise GazeboError(f"Could not open file[{name}]: not a file, nor found on GAZEBO_RESOURCE_PATH "
                      f"({env.get('GAZEBO_RESOURCE_PATH', '')!r}) or in kame's worlds ({shipped}/worlds)")
