"""SDF 1.4 to 1.7 worlds and models read into kame.gazebo.description's values.

Understood: <world> with <physics> (max_step_size, real_time_update_rate, real_time_factor;
<gravity> in the world or, as SDF 1.4 put it, in <physics>), <scene> (ambient, background),
<light>, <model>, <include> and <plugin>; <model> with <static>, <pose>, <link>, <joint>, <frame>,
<plugin>, nested <model> and <include> (flattened, their links named "inner::link"; an included
folder may hold a URDF); <link> with <inertial>, <visual>, <collision> (surface friction mu, mu2),
<sensor> (its plugins), <gravity>, <kinematic>, <self_collide>; geometry box, cylinder, sphere,
plane and mesh; joints revolute, continuous, prismatic, fixed and ball, with <limit> and <dynamics>
(damping, friction, spring_stiffness, spring_reference).
Poses: <pose relative_to="frame"> (1.7) and <pose frame="frame"> (1.5, 1.6) name a link, joint,
<frame> or nested model of the same model ("__model__" or nothing: the model; a world's models
may be placed relative to another model). Joint axes are in the joint's frame, or the model's with
<use_parent_model_frame> and in SDF 1.4, or in <xyz expressed_in="frame">.
What kame cannot simulate (heightmaps, actors, revolute2/universal/screw/gearbox joints) is left
out with a warning, and the rest of the world runs. Malformed input raises GazeboError naming
the file, line and element.
"""

from __future__ import annotations

import math
from dataclasses import replace

from kame.gazebo import description as d
from kame.gazebo.errors import GazeboError
from kame.gazebo.materials import script_color
from kame.gazebo.poses import Pose, Vector3, pose_of
from kame.gazebo.resources import Resources, read_xml
from kame.gazebo.urdf import UrdfReader
from kame.gazebo.xmltree import Element, parse_vector

JOINT_TYPES = {"revolute", "continuous", "prismatic", "fixed", "ball"}
MODEL_FRAME = "__model__"


def color_of(material: Element | None) -> d.Color:
    if material is None:
        return d.GRAY
    color: d.Color | None = None
    for tag in ("diffuse", "ambient"):
        found = material.child(tag)
        if found is not None and found.text.strip():
            parts = found.text.split()
            values = parse_vector(found.text, len(parts) if len(parts) in (3, 4) else 4, found)
            color = (values[0], values[1], values[2], values[3] if len(values) == 4 else 1.0)
            break
    script = material.child("script")
    if color is None and script is not None:
        color = script_color(script.child_text("name") or "")
    return color or d.GRAY


def geometry_of(owner: Element, resources: Resources) -> d.Geometry | str:
    """The <geometry> of a visual or collision, or why kame leaves it out."""
    geometry = owner.child("geometry")
    shape = next(iter(geometry.children), None) if geometry is not None else None
    if shape is None:
        return f"{owner.where()} has no geometry"
    if shape.tag == "box":
        return d.Geometry("box", shape.vector("size", (1.0, 1.0, 1.0)))
    if shape.tag == "cylinder":
        return d.Geometry("cylinder", (shape.number("radius", 1.0), shape.number("length", 1.0)))
    if shape.tag == "sphere":
        return d.Geometry("sphere", (shape.number("radius", 1.0),))
    if shape.tag == "plane":
        normal = shape.vector("normal", (0.0, 0.0, 1.0))
        return d.Geometry("plane", shape.vector("size", (0.0, 0.0)), normal=(normal[0], normal[1], normal[2]))
    if shape.tag == "mesh":
        uri = shape.child_text("uri") or ""
        if not uri:
            raise GazeboError(f"{shape.where()}: a mesh needs a <uri>")
        scale = shape.vector("scale", (1.0, 1.0, 1.0))
        return d.Geometry("mesh", mesh_uri=uri, mesh_file=resources.path(uri, shape),
                          scale=(scale[0], scale[1], scale[2]))
    return f"{shape.where()}: {shape.tag} geometry is not simulated by kame; left out"


class SdfReader:
    """Reads SDF elements; `warnings` collects what was left out."""

    def __init__(self, resources: Resources) -> None:
        self.resources = resources
        self.warnings: list[str] = []

    # ------------------------------------------------------------------ documents

    def world(self, root: Element) -> d.World:
        """A <sdf> document with a <world> (or with models only: they make the world)."""
        version = self._version(root)
        world = root.child("world")
        if world is None:
            alone = tuple(self.model(m, version) for m in root.each("model"))
            if not alone:
                raise GazeboError(f"{root.where()}: neither a <world> nor a <model> in it")
            return d.World(models=alone, source=root.source)
        physics = self._physics(world)
        models: list[d.Model] = []
        lights = [self._light(e) for e in world.each("light")]
        placed: dict[str, Pose] = {}
        for child in world.children:
            if child.tag == "model":
                model = self.model(child, version, placed)
            elif child.tag == "include":
                included = self._include_in_world(child, placed)
                if isinstance(included, d.Light):
                    lights.append(included)
                    continue
                model = included
            else:
                continue
            if model.name in placed:
                raise GazeboError(f"{child.where()}: a second model named {model.name!r}")
            placed[model.name] = model.pose
            models.append(model)
        for child in world.children:
            if child.tag in ("actor", "road", "population"):
                self.warnings.append(f"{child.where()}: <{child.tag}> is not simulated by kame; left out")
        plugins = tuple(self._plugin(e, "", "", "") for e in world.each("plugin"))
        return d.World(world.attrs.get("name", "default"), physics, self._scene(world.child("scene")), tuple(models),
                       tuple(lights), plugins, root.source)

    def _scene(self, scene: Element | None) -> d.Scene:
        if scene is None:
            return d.Scene()
        defaults = d.Scene()
        colors = [color_of(_as_material(scene, tag)) if scene.child(tag) is not None else default
                  for tag, default in (("ambient", defaults.ambient), ("background", defaults.background))]
        return d.Scene(*colors)

    def _include_in_world(self, element: Element, placed: dict[str, Pose]) -> d.Model | d.Light:
        """An included model, or an included light (model://sun is a <light>, not a <model>)."""
        uri = element.child_text("uri")
        if not uri:
            raise GazeboError(f"{element.where()}: an <include> needs a <uri>")
        root = read_xml(self.resources.model_file(self.resources.path(uri, element), element))
        light = root.child("light")
        if light is None or root.child("model") is not None:
            return self.include(element, placed)
        found = self._light(light)
        pose, _ = pose_of(element)
        return replace(found, name=element.child_text("name") or found.name,
                       pose=pose if element.child("pose") is not None else found.pose)

    def model_document(self, root: Element, name: str = "") -> d.Model:
        """The one model of a <sdf> document (spawn_model -sdf), renamed to `name` when given."""
        version = self._version(root)
        element = root.child("model")
        if element is None:
            world = root.child("world")
            element = world.child("model") if world is not None else None
        if element is None:
            raise GazeboError(f"{root.where()}: no <model> in it")
        model = self.model(element, version)
        return replace(model, name=name) if name else model

    def include(self, element: Element, placed: dict[str, Pose] | None = None) -> d.Model:
        uri = element.child_text("uri")
        if not uri:
            raise GazeboError(f"{element.where()}: an <include> needs a <uri>")
        folder = self.resources.path(uri, element)
        root = read_xml(self.resources.model_file(folder, element))
        if root.tag == "robot":  # a model folder may hold a URDF (model.config's <sdf> names the file)
            urdf = UrdfReader(self.resources)
            model = urdf.model(root, element.child_text("name") or "")
            self.warnings += urdf.warnings
        else:
            model = self.model_document(root, element.child_text("name") or "")
        pose, relative_to = pose_of(element)
        if element.child("pose") is not None:
            model = replace(model, pose=_placed(pose, relative_to, placed or {}, element))
        if element.child("static") is not None:
            model = replace(model, static=element.flag("static", False))
        # SDF 1.6 lets an <include> carry plugins for the model it includes
        added = tuple(self._plugin(p, model.name, "", "") for p in element.each("plugin"))
        return replace(model, plugins=model.plugins + added) if added else model

    def _version(self, root: Element) -> tuple[int, ...]:
        if root.tag != "sdf":
            raise GazeboError(f"{root.where()}: expected an <sdf> document, not <{root.tag}>")
        return tuple(_version_numbers(root.attrs.get("version", "1.7")))

    # ------------------------------------------------------------------ world parts

    def _physics(self, world: Element) -> d.Physics:
        physics = world.child("physics")
        gravity: tuple[float, ...] = (0.0, 0.0, -9.8)
        if physics is not None:
            gravity = physics.vector("gravity", gravity)
        gravity = world.vector("gravity", gravity)
        if physics is None:
            return d.Physics(gravity=(gravity[0], gravity[1], gravity[2]))
        values = d.Physics(physics.number("max_step_size", 0.001), physics.number("real_time_update_rate", 1000.0),
                           physics.number("real_time_factor", 1.0), (gravity[0], gravity[1], gravity[2]))
        if not values.max_step_size > 0 or not math.isfinite(values.max_step_size):
            raise GazeboError(f"{physics.where()}: max_step_size must be above 0, not {values.max_step_size}")
        return values

    def _light(self, element: Element) -> d.Light:
        pose, _ = pose_of(element)
        direction = element.vector("direction", (0.0, 0.0, -1.0))
        attenuation = element.child("attenuation")
        return d.Light(element.attrs.get("name", "light"), element.attrs.get("type", "point"), pose,
                       color_of(_as_material(element, "diffuse")), color_of(_as_material(element, "specular")),
                       (direction[0], direction[1], direction[2]), element.flag("cast_shadows", False),
                       attenuation.number("range", 10.0) if attenuation is not None else 10.0)

    def _plugin(self, element: Element, model: str, link: str, sensor: str) -> d.Plugin:
        return d.Plugin(element.attrs.get("name", ""), element.attrs.get("filename", ""), model, link, sensor, element)

    # ------------------------------------------------------------------ models

    def model(self, element: Element, version: tuple[int, ...], placed: dict[str, Pose] | None = None) -> d.Model:
        name = element.attrs.get("name", "").strip()
        if not name:
            raise GazeboError(f"{element.where()}: a <model> needs a name")
        pose, relative_to = pose_of(element)
        frames = _Frames(element)
        raw_links: list[tuple[Element, str]] = []
        nested: list[d.Model] = []
        for child in element.children:
            if child.tag == "link":
                raw_links.append((child, child.attrs.get("name", "")))
                frames.add(child.attrs.get("name", ""), child, MODEL_FRAME)
            elif child.tag == "frame":
                attached_to = child.attrs.get("attached_to", "") or MODEL_FRAME
                frames.add(child.attrs.get("name", ""), child, attached_to)
            elif child.tag in ("model", "include"):
                inner = self.model(child, version) if child.tag == "model" else self.include(child)
                inner_pose, inner_relative = pose_of(child)
                if child.tag == "include" and child.child("pose") is None:
                    inner_pose = inner.pose
                frames.add_pose(inner.name, inner_pose, inner_relative or MODEL_FRAME, child)
                for link in inner.links:  # the outer model's joints name them "inner::link"
                    frames.add_pose(f"{inner.name}::{link.name}", link.pose, inner.name, child)
                nested.append(inner)
        for joint in element.each("joint"):
            frames.add(joint.attrs.get("name", ""), joint, joint.child_text("child") or MODEL_FRAME)
        self_collide = element.flag("self_collide", False)
        links = [self._link(e, link_name, frames, self_collide) for e, link_name in raw_links]
        joints = [self._joint(e, frames, version) for e in element.each("joint")]
        plugins = [self._plugin(e, name, "", "") for e in element.each("plugin")]
        for link_element, link_name in raw_links:
            for sensor in link_element.each("sensor"):
                sensor_name = sensor.attrs.get("name", "")
                plugins += [self._plugin(p, name, link_name, sensor_name) for p in sensor.each("plugin")]
        for inner in nested:
            inner_pose = frames.resolve(inner.name)
            links += [replace(link, name=f"{inner.name}::{link.name}", pose=inner_pose * link.pose)
                      for link in inner.links]
            joints += [replace(j, name=f"{inner.name}::{j.name}", parent=_prefixed(inner.name, j.parent),
                               child=_prefixed(inner.name, j.child)) for j in inner.joints]
            plugins += [replace(p, model=name, link=_prefixed(inner.name, p.link) if p.link else "")
                        for p in inner.plugins]
        if not links:
            self.warnings.append(f"{element.where()}: model {name!r} has no links")
        return d.Model(name, _placed(pose, relative_to, placed or {}, element), element.flag("static", False),
                       tuple(links), tuple(joints), tuple(plugins), element.source)

    def _link(self, element: Element, name: str, frames: _Frames, self_collide: bool) -> d.Link:
        if not name:
            raise GazeboError(f"{element.where()}: a <link> needs a name")
        in_model = frames.resolve(name)
        to_link = in_model.inverse()

        def local(part: Element) -> Pose:
            pose, relative_to = pose_of(part)
            if not relative_to or relative_to == name:
                return pose
            return to_link * frames.resolve(relative_to, part) * pose

        visuals: list[d.Visual] = []
        for v in element.each("visual"):
            geometry = geometry_of(v, self.resources)
            if isinstance(geometry, str):
                self.warnings.append(geometry)
                continue
            color = color_of(v.child("material"))
            transparency = v.number("transparency", 0.0)
            visuals.append(d.Visual(v.attrs.get("name", "visual"), geometry, local(v),
                                    (*color[:3], color[3] * (1.0 - transparency))))
        collisions: list[d.Collision] = []
        for c in element.each("collision"):
            geometry = geometry_of(c, self.resources)
            if isinstance(geometry, str):
                self.warnings.append(geometry)
                continue
            mu, mu2 = _friction(c)
            name_in_sdf = c.attrs.get("name", "collision")
            collisions.append(d.Collision(name_in_sdf, geometry, local(c), mu, mu2, f"{name}::{name_in_sdf}"))
        sensors = [d.Sensor(s.attrs.get("name", ""), s.attrs.get("type", ""), local(s), s.number("update_rate", 0.0),
                            s.flag("always_on", False), s.flag("visualize", False), s) for s in element.each("sensor")]
        return d.Link(name, in_model, self._inertial(element.child("inertial")), tuple(visuals), tuple(collisions),
                      tuple(sensors), element.flag("gravity", True), element.flag("kinematic", False),
                      element.flag("self_collide", self_collide))

    def _inertial(self, element: Element | None) -> d.Inertial:
        if element is None:
            return d.Inertial()
        pose, _ = pose_of(element)
        inertia = element.child("inertia")
        mass = element.number("mass", 1.0)
        if not mass > 0 or not math.isfinite(mass):
            raise GazeboError(f"{element.where()}: a link's mass must be above 0, not {mass}")
        if inertia is None:
            return d.Inertial(mass, pose)
        moments = (inertia.number(key, 1.0 if key in ("ixx", "iyy", "izz") else 0.0)
                   for key in ("ixx", "iyy", "izz", "ixy", "ixz", "iyz"))
        return d.Inertial(mass, pose, *moments)

    def _joint(self, element: Element, frames: _Frames, version: tuple[int, ...]) -> d.Joint:
        name = element.attrs.get("name", "")
        kind = element.attrs.get("type", "")
        parent, child = element.child_text("parent") or "", element.child_text("child") or ""
        if not name or not parent or not child:
            raise GazeboError(f"{element.where()}: a <joint> needs a name, a <parent> and a <child>")
        if kind not in JOINT_TYPES:
            self.warnings.append(f"{element.where()}: {kind!r} joints are not simulated by kame; joint {name!r} "
                                 f"is fixed instead")
            kind = "fixed"
        child_in_model = frames.resolve(child, element)
        joint_in_model = frames.resolve(name)
        axis_element = element.child("axis")
        axis = d.JointAxis((0.0, 0.0, 1.0))
        if axis_element is not None:
            xyz = axis_element.vector("xyz", (0.0, 0.0, 1.0))
            norm = math.sqrt(sum(v * v for v in xyz))
            if not norm > 0 or not math.isfinite(norm):
                raise GazeboError(f"{axis_element.where()}: a joint axis must be a non-zero vector")
            in_model_frame = version < (1, 5) or axis_element.flag("use_parent_model_frame", False)
            expressed_in = (axis_element.child("xyz") or axis_element).attrs.get("expressed_in", "")
            direction: Vector3 = (xyz[0] / norm, xyz[1] / norm, xyz[2] / norm)
            if expressed_in:
                in_model = frames.resolve(expressed_in, axis_element)
                direction = _rotate(joint_in_model.inverse() * in_model, direction)
            elif in_model_frame:
                direction = _rotate(joint_in_model.inverse(), direction)
            limit, dynamics = axis_element.child("limit"), axis_element.child("dynamics")
            axis = d.JointAxis(
                direction,
                limit.number("lower", -1e16) if limit is not None else -1e16,
                limit.number("upper", 1e16) if limit is not None else 1e16,
                limit.number("effort", -1.0) if limit is not None else -1.0,
                limit.number("velocity", -1.0) if limit is not None else -1.0,
                dynamics.number("damping", 0.0) if dynamics is not None else 0.0,
                dynamics.number("friction", 0.0) if dynamics is not None else 0.0,
                dynamics.number("spring_stiffness", 0.0) if dynamics is not None else 0.0,
                dynamics.number("spring_reference", 0.0) if dynamics is not None else 0.0)
            if kind == "continuous":
                axis = replace(axis, lower=-1e16, upper=1e16)
        return d.Joint(name, kind, parent, child, child_in_model.inverse() * joint_in_model, axis)


class _Frames:
    """A model's named frames (links, joints, <frame>s, nested models) and their poses in the
    model's frame, resolved on demand; a cycle or an unknown name is a GazeboError."""

    def __init__(self, model: Element) -> None:
        self.model = model
        self._raw: dict[str, tuple[Pose, str, Element]] = {}
        self._resolved: dict[str, Pose] = {MODEL_FRAME: Pose(), "": Pose()}
        self._visiting: set[str] = set()

    def add(self, name: str, element: Element, default_relative_to: str) -> None:
        pose, relative_to = pose_of(element)
        self.add_pose(name, pose, relative_to or default_relative_to, element)

    def add_pose(self, name: str, pose: Pose, relative_to: str, element: Element) -> None:
        if name:
            self._raw[name] = (pose, relative_to, element)

    def resolve(self, name: str, asked_by: Element | None = None) -> Pose:
        if name in self._resolved:
            return self._resolved[name]
        if name == self.model.attrs.get("name"):
            return Pose()
        if name not in self._raw:
            where = (asked_by or self.model).where()
            raise GazeboError(f"{where}: no frame, link or joint named {name!r} in model "
                              f"{self.model.attrs.get('name', '')!r}")
        pose, relative_to, element = self._raw[name]
        if name in self._visiting:
            raise GazeboError(f"{element.where()}: the poses of {name!r} are relative to each other in a cycle")
        self._visiting.add(name)
        base = self.resolve(relative_to, element) if relative_to != name else Pose()
        self._visiting.discard(name)
        self._resolved[name] = base * pose
        return self._resolved[name]


def _placed(pose: Pose, relative_to: str, placed: dict[str, Pose], element: Element) -> Pose:
    if not relative_to or relative_to == "world":
        return pose
    if relative_to not in placed:
        raise GazeboError(f"{element.where()}: the pose is relative to {relative_to!r}, which is not a model "
                          f"placed before it in the world")
    return placed[relative_to] * pose


def _friction(collision: Element) -> tuple[float, float]:
    surface = collision.child("surface")
    friction = surface.child("friction") if surface is not None else None
    ode = friction.child("ode") if friction is not None else None
    if ode is None:
        return 1.0, 1.0
    mu = ode.number("mu", 1.0)
    mu2 = ode.number("mu2", mu)
    if mu < 0 or mu2 < 0 or not math.isfinite(mu) or not math.isfinite(mu2):
        raise GazeboError(f"{ode.where()}: friction coefficients must be finite and at least 0")
    return mu, mu2


def _as_material(owner: Element, tag: str) -> Element | None:
    found = owner.child(tag)
    if found is None:
        return None
    return Element("material", {}, found.line, found.source, [Element("diffuse", {}, found.line, found.source,
                                                                      text=found.text)])


def _rotate(pose: Pose, vector: Vector3) -> Vector3:
    v = pose.rotation() @ vector
    return float(v[0]), float(v[1]), float(v[2])


def _prefixed(prefix: str, name: str) -> str:
    return name if name == "world" else f"{prefix}::{name}"


def _version_numbers(text: str) -> list[int]:
    return [int(part) if part.isdigit() else 0 for part in text.strip().split(".")]
