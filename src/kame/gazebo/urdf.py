"""URDF robots read into a kame.gazebo.description Model, as `spawn_model -urdf` hands them to Gazebo.

- Links, joints (revolute, continuous, prismatic, fixed; floating and planar are fixed, with a
  warning), <inertial>, <visual>, <collision>, materials by name or colour; meshes through the
  package finder. A link's frame is its parent joint's frame, as URDF defines it.
- Fixed joints are kept, not lumped: MuJoCo welds the child link to its parent, so every link
  keeps its name and the lumped result's inertia is the same. Each collision also carries the
  link and name Gazebo's lumping gives it ("base_footprint::base_footprint_fixed_joint_lump__
  base_link_collision"), which contact sensors and bumper messages written for Gazebo name. A
  link without <inertial> gets a negligible mass (Gazebo would drop it; here it still carries its
  visuals and collisions).
- <gazebo reference="link">: <material> (a Gazebo material script name: the link's visuals take
  its colour), <mu1>, <mu2>, <gravity>/<turnGravityOff>, <sensor> (its <pose> in the link's frame,
  its plugins). <gazebo> without a reference: <plugin> (the model's), <static>.
  Collisions are named "<link>_collision" (then _1, _2...), visuals "<link>_visual", as Gazebo's
  URDF conversion names them.
"""

from __future__ import annotations

import math
from dataclasses import replace

from kame.gazebo import description as d
from kame.gazebo.errors import GazeboError
from kame.gazebo.materials import script_color
from kame.gazebo.poses import Pose, pose_of
from kame.gazebo.resources import Resources
from kame.gazebo.xmltree import Element, parse_vector

MASSLESS = d.Inertial(1e-6, Pose(), 1e-9, 1e-9, 1e-9)


def origin_of(element: Element) -> Pose:
    origin = element.child("origin")
    if origin is None:
        return Pose()
    xyz = parse_vector(origin.attrs.get("xyz", "0 0 0"), 3, origin)
    rpy = parse_vector(origin.attrs.get("rpy", "0 0 0"), 3, origin)
    if not all(math.isfinite(v) for v in (*xyz, *rpy)):
        raise GazeboError(f"{origin.where()}: an origin must be finite")
    return Pose.from_xyz_rpy(*xyz, *rpy)


def _attr_float(element: Element, name: str, default: float) -> float:
    text = element.attrs.get(name)
    if text is None or not text.strip():
        return default
    return parse_vector(text, 1, element)[0]


class UrdfReader:
    def __init__(self, resources: Resources) -> None:
        self.resources = resources
        self.warnings: list[str] = []

    def model(self, root: Element, name: str = "") -> d.Model:
        if root.tag != "robot":
            raise GazeboError(f"{root.where()}: expected a URDF <robot>, not <{root.tag}>")
        robot = name or root.attrs.get("name", "").strip()
        if not robot:
            raise GazeboError(f"{root.where()}: the robot needs a name")
        colors = {m.attrs.get("name", ""): self._color(m) for m in root.each("material")}
        extensions: dict[str, list[Element]] = {}
        for gazebo in root.each("gazebo"):
            extensions.setdefault(gazebo.attrs.get("reference", ""), []).extend(gazebo.children)
        joints = [self._joint(j) for j in root.each("joint")]
        # a link named "world" is the world itself (a robot fixed in place hangs on it), as Gazebo reads it
        link_elements = {e.attrs.get("name", ""): e for e in root.each("link") if e.attrs.get("name") != "world"}
        if "" in link_elements:
            raise GazeboError(f"{link_elements[''].where()}: a <link> needs a name")
        if not link_elements:
            raise GazeboError(f"{root.where()}: the robot has no links")
        parent_of = {j.child: j for j, _ in joints}
        for joint, element in joints:
            for end in (joint.parent, joint.child):
                if end not in link_elements and not (end == "world" and end == joint.parent):
                    raise GazeboError(f"{element.where()}: joint {joint.name!r} names link {end!r}, which the robot "
                                      f"does not have")
        poses: dict[str, Pose] = {}

        def pose_in_model(link: str, seen: tuple[str, ...] = ()) -> Pose:
            if link not in poses:
                if link in seen:
                    raise GazeboError(f"{root.source}: the joints of link {link!r} form a loop")
                joint_and_origin = parent_of.get(link)
                if joint_and_origin is None:
                    poses[link] = Pose()
                elif joint_and_origin.parent == "world":
                    poses[link] = joint_and_origin.pose
                else:
                    poses[link] = pose_in_model(joint_and_origin.parent, (*seen, link)) * joint_and_origin.pose
            return poses[link]

        def lumped_into(link: str) -> str:
            """The link Gazebo lumps `link` into: its nearest ancestor not on a fixed joint."""
            while link in parent_of and parent_of[link].type == "fixed" and parent_of[link].parent != "world":
                link = parent_of[link].parent
            return link

        links = [self._link(e, pose_in_model(n), colors, extensions.get(n, []), lumped_into(n))
                 for n, e in link_elements.items()]
        plugins = [d.Plugin(p.attrs.get("name", ""), p.attrs.get("filename", ""), robot, "", "", p)
                   for p in extensions.get("", []) if p.tag == "plugin"]
        for link in links:
            plugins += [d.Plugin(p.attrs.get("name", ""), p.attrs.get("filename", ""), robot, link.name, s.name, p)
                        for s in link.sensors for p in s.element.each("plugin")]
        static_flags = [e for e in extensions.get("", []) if e.tag == "static"]
        static = bool(static_flags) and static_flags[-1].text.strip().lower() in ("1", "true")
        # a joint's frame is its child link's frame in URDF: the joint pose within the child is the identity
        model_joints = tuple(replace(j, pose=Pose()) for j, _ in joints)
        return d.Model(robot, Pose(), static, tuple(links), model_joints, tuple(plugins), root.source)

    def _color(self, material: Element) -> d.Color:
        color = material.child("color")
        if color is not None and "rgba" in color.attrs:
            r, g, b, a = parse_vector(color.attrs["rgba"], 4, color)
            return r, g, b, a
        return d.GRAY

    def _joint(self, element: Element) -> tuple[d.Joint, Element]:
        name, kind = element.attrs.get("name", ""), element.attrs.get("type", "")
        parent, child = element.child("parent"), element.child("child")
        if not name or parent is None or child is None or "link" not in parent.attrs or "link" not in child.attrs:
            raise GazeboError(f"{element.where()}: a <joint> needs a name, a <parent link=...> and a <child link=...>")
        if kind in ("floating", "planar"):
            self.warnings.append(f"{element.where()}: {kind} joints are not simulated by kame; joint {name!r} is fixed")
            kind = "fixed"
        elif kind not in ("revolute", "continuous", "prismatic", "fixed"):
            raise GazeboError(f"{element.where()}: unknown joint type {kind!r}")
        axis_element, limit, dynamics = element.child("axis"), element.child("limit"), element.child("dynamics")
        xyz = parse_vector(axis_element.attrs.get("xyz", "1 0 0"), 3, axis_element) if axis_element else (1.0, 0, 0)
        norm = math.sqrt(sum(v * v for v in xyz))
        if not norm > 0 or not math.isfinite(norm):
            raise GazeboError(f"{(axis_element or element).where()}: a joint axis must be a non-zero vector")
        axis = d.JointAxis((xyz[0] / norm, xyz[1] / norm, xyz[2] / norm))
        if limit is not None:  # a continuous joint's effort and velocity limits hold too; its range does not
            axis = replace(axis, effort=_attr_float(limit, "effort", -1.0),
                           velocity=_attr_float(limit, "velocity", -1.0))
            if kind != "continuous":
                axis = replace(axis, lower=_attr_float(limit, "lower", 0.0), upper=_attr_float(limit, "upper", 0.0))
        if dynamics is not None:
            axis = replace(axis, damping=_attr_float(dynamics, "damping", 0.0),
                           friction=_attr_float(dynamics, "friction", 0.0))
        # the origin is the child link's pose in the parent's frame; kept here until the link poses are known
        return d.Joint(name, kind, parent.attrs["link"], child.attrs["link"], origin_of(element), axis), element

    def _link(self, element: Element, pose: Pose, colors: dict[str, d.Color], extensions: list[Element],
              lumped_into: str) -> d.Link:
        name = element.attrs["name"]
        gazebo_material = next((e.text.strip() for e in reversed(extensions) if e.tag == "material"), "")
        mu1 = next((float(e.text) for e in reversed(extensions) if e.tag == "mu1" and _number(e)), None)
        mu2 = next((float(e.text) for e in reversed(extensions) if e.tag == "mu2" and _number(e)), None)
        visuals = []
        for index, v in enumerate(element.each("visual")):
            geometry = self._geometry(v)
            color = script_color(gazebo_material) if gazebo_material else self._visual_color(v, colors)
            visuals.append(d.Visual(v.attrs.get("name") or _indexed(f"{name}_visual", index), geometry, origin_of(v),
                                    color))
        collisions = []
        for index, c in enumerate(element.each("collision")):
            mu = mu1 if mu1 is not None else 1.0
            own = _indexed(f"{name}_collision", index)
            # Gazebo merges a link on fixed joints into its ancestor, renaming its collisions (a contact
            # sensor's <collision> names them so); kame keeps the link and gives the name beside it
            in_gazebo = f"{name}::{own}" if lumped_into == name else (
                f"{lumped_into}::{lumped_into}_fixed_joint_lump__{own}")
            collisions.append(d.Collision(own, self._geometry(c), origin_of(c), mu, mu2 if mu2 is not None else mu,
                                          in_gazebo))
        sensors = []
        for s in (e for e in extensions if e.tag == "sensor"):
            sensor_pose, _ = pose_of(s)
            sensors.append(d.Sensor(s.attrs.get("name", ""), s.attrs.get("type", ""), sensor_pose,
                                    s.number("update_rate", 0.0), s.flag("always_on", False),
                                    s.flag("visualize", False), s))
        gravity, self_collide = True, False
        for e in extensions:
            if e.tag == "gravity":
                gravity = e.text.strip().lower() in ("1", "true")
            elif e.tag == "turnGravityOff":
                gravity = e.text.strip().lower() not in ("1", "true")
            elif e.tag == "selfCollide":
                self_collide = e.text.strip().lower() in ("1", "true")
        return d.Link(name, pose, self._inertial(element.child("inertial")), tuple(visuals), tuple(collisions),
                      tuple(sensors), gravity, self_collide=self_collide)

    def _inertial(self, element: Element | None) -> d.Inertial:
        if element is None:
            return MASSLESS
        mass_element, inertia = element.child("mass"), element.child("inertia")
        mass = _attr_float(mass_element, "value", 0.0) if mass_element is not None else 0.0
        if not math.isfinite(mass) or mass < 0:
            raise GazeboError(f"{element.where()}: a link's mass must be finite and at least 0, not {mass}")
        if mass == 0:
            return MASSLESS
        if inertia is None:
            return d.Inertial(mass, origin_of(element))
        values = [_attr_float(inertia, key, 0.0) for key in ("ixx", "iyy", "izz", "ixy", "ixz", "iyz")]
        return d.Inertial(mass, origin_of(element), *values)

    def _visual_color(self, visual: Element, colors: dict[str, d.Color]) -> d.Color:
        material = visual.child("material")
        if material is None:
            return d.GRAY
        if material.child("color") is not None:
            return self._color(material)
        return colors.get(material.attrs.get("name", ""), d.GRAY)

    def _geometry(self, owner: Element) -> d.Geometry:
        geometry = owner.child("geometry")
        shape = next(iter(geometry.children), None) if geometry is not None else None
        if shape is None:
            raise GazeboError(f"{owner.where()}: no <geometry> in it")
        if shape.tag == "box":
            return d.Geometry("box", parse_vector(shape.attrs.get("size", "1 1 1"), 3, shape))
        if shape.tag == "cylinder":
            return d.Geometry("cylinder", (_attr_float(shape, "radius", 1.0), _attr_float(shape, "length", 1.0)))
        if shape.tag == "sphere":
            return d.Geometry("sphere", (_attr_float(shape, "radius", 1.0),))
        if shape.tag == "mesh":
            uri = shape.attrs.get("filename", "")
            if not uri:
                raise GazeboError(f"{shape.where()}: a mesh needs a filename")
            scale = parse_vector(shape.attrs.get("scale", "1 1 1"), 3, shape)
            return d.Geometry("mesh", mesh_uri=uri, mesh_file=self.resources.path(uri, shape),
                              scale=(scale[0], scale[1], scale[2]))
        raise GazeboError(f"{shape.where()}: unknown URDF geometry <{shape.tag}>")


def _indexed(name: str, index: int) -> str:
    return name if index == 0 else f"{name}_{index}"


def _number(element: Element) -> bool:
    try:
        return math.isfinite(float(element.text))
    except ValueError:
        raise GazeboError(f"{element.where()}: expected a number, not {element.text.strip()!r}") from None
