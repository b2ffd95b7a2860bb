"""Models described by SDF or URDF added to a MuJoCo MjSpec: one body per link, named
"model::link" as Gazebo names links.

How Gazebo's concepts map onto MuJoCo's:
- A model's links form trees along its joints: a link is a body inside its parent link's body;
  a fixed joint is a child body with no joint (welded, not lumped: each link keeps its name and
  its own inertia). A link with no parent joint hangs on a free joint, or on the world when the
  model is <static> or the link's joint names "world" as parent. A joint that would close a
  loop is left out with a warning (MuJoCo's bodies form a tree).
- Visuals are geoms in VISUAL_GROUP that collide with nothing; collisions are geoms in
  COLLISION_GROUP, which cameras do not draw and rays hit. A mesh collides as its convex hull
  (MuJoCo's rule: a room or an arch made of one mesh is solid to other bodies; rays and cameras
  see the mesh itself). Inertia is the link's <inertial>, never computed from geoms.
- Friction: Gazebo (ODE) takes the smaller `mu` of two touching surfaces, MuJoCo the larger,
  unless one geom has a higher priority: so a collision's priority ranks its mu, lowest mu
  highest (`rank_friction`). `mu2` (ODE's second direction, across <fdir1> or an axis ODE picks
  from the contact normal) cannot be simulated apart: MuJoCo's friction is isotropic with the
  cone used here, its contact frame's axes are its colliders' choice. A collision takes the
  smaller of its mu and mu2, so a contact grips as the weaker of ODE's two directions (ODE takes
  the smaller per direction of the two surfaces; the smaller of those is this): nothing slides
  in kame that would hold in Gazebo in one direction only, never the other way round. A model
  whose smaller coefficient is below 1 (Gazebo's default, where it matters against ordinary
  surfaces) is warned about once.
- Every hinge and slide joint has a velocity actuator, idle (gain 0) until a drive asks for
  it: MuJoCo integrates an actuator's velocity gain implicitly, so a stiff wheel drive stays
  stable where a force computed outside the step would not.
- Camera and depth sensors are MuJoCo cameras (looking along the sensor's +x, up +z, as Gazebo's);
  an IMU is a site with MuJoCo's gyro, accelerometer and orientation sensors.
- <gravity>false</gravity> on a link is MuJoCo's gravity compensation.
- A model's links do not collide with each other unless both say <self_collide> (Gazebo's
  default), by MuJoCo exclusions between their bodies.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from kame.gazebo import description as d
from kame.gazebo.engine import mujoco
from kame.gazebo.errors import GazeboError
from kame.gazebo.poses import Pose

VISUAL_GROUP = 0
COLLISION_GROUP = 3
CAMERA_TYPES = frozenset({"camera", "depth", "multicamera", "wideanglecamera"})
# MuJoCo's cameras look along -z with +y up; Gazebo's along +x with +z up
OPTICAL = Pose.from_xyz_rpy(0.0, 0.0, 0.0, math.pi / 2, 0.0, -math.pi / 2)
MeshLoader = Callable[[d.Geometry], tuple[np.ndarray, np.ndarray]]  # vertices (N x 3), faces (M x 3)


def drive_name(joint: str) -> str:
    return f"{joint}::drive"


def free_joint_name(body: str) -> str:
    return f"{body}::free"


def sensor_object_name(model: str, link: str, sensor: str) -> str:
    return f"{model}::{link}::{sensor}"


def add_model(spec: mujoco.MjSpec, model: d.Model, load_mesh: MeshLoader, warnings: list[str]) -> None:
    """Adds `model`'s bodies to `spec`; GazeboError when a link or joint is wrong."""
    links = {link.name: link for link in model.links}
    parent_joint: dict[str, d.Joint] = {}
    for joint in model.joints:
        for end in (joint.parent, joint.child):
            if end != "world" and end not in links:
                raise GazeboError(f"model {model.name!r} ({model.source}): joint {joint.name!r} names link "
                                  f"{end!r}, which the model does not have")
        if joint.child in parent_joint:
            warnings.append(f"model {model.name!r}: joint {joint.name!r} would close a loop at link "
                            f"{joint.child!r}; left out")
            continue
        parent_joint[joint.child] = joint
    children: dict[str, list[str]] = {}
    for child, joint in parent_joint.items():
        children.setdefault(joint.parent, []).append(child)
    roots = [name for name in links if name not in parent_joint or parent_joint[name].parent == "world"]
    placed: set[str] = set()
    anisotropic: list[str] = []

    def add(name: str, parent_body: mujoco.MjsBody, parent_pose: Pose) -> None:
        link = links[name]
        world_pose = model.pose * link.pose
        body = parent_body.add_body(name=f"{model.name}::{name}")
        relative = parent_pose.inverse() * world_pose
        body.pos, body.quat = relative.position, relative.mj_quat()
        _inertia(body, link)
        if not link.gravity:
            body.gravcomp = 1.0
        joint = parent_joint.get(name)
        if joint is not None and joint.type != "fixed" and not model.static:
            _joint(spec, body, model.name, joint)
        elif joint is None and not model.static:
            body.add_freejoint(name=free_joint_name(f"{model.name}::{name}"))
        _geoms(spec, body, model.name, link, load_mesh)
        anisotropic.extend(f"{name}::{c.name}" for c in link.collisions if min(c.mu2, 1.0) != min(c.mu, 1.0))
        placed.add(name)
        for child in children.get(name, []):
            if child in placed:
                continue
            add(child, body, world_pose)

    for root in roots:
        add(root, spec.worldbody, Pose())
    for name in links:
        if name not in placed:  # only reachable through a loop: hang it on a free joint of its own
            add(name, spec.worldbody, Pose())
    if anisotropic:
        warnings.append(f"model {model.name!r}: collisions {', '.join(anisotropic)} give <mu2> apart from <mu>; "
                        "MuJoCo's friction is the same in every direction, so each takes the smaller")
    _exclude_self_collisions(spec, model)


def _exclude_self_collisions(spec: mujoco.MjSpec, model: d.Model) -> None:
    """A model's links touch each other only where both say <self_collide> (MuJoCo already leaves
    out a body and its parent, and bodies welded together)."""
    colliding = [link for link in model.links if link.collisions]
    for i, first in enumerate(colliding):
        for second in colliding[i + 1:]:
            if not (first.self_collide and second.self_collide):
                spec.add_exclude(name=f"{model.name}::exclude::{first.name}::{second.name}",
                                 bodyname1=f"{model.name}::{first.name}", bodyname2=f"{model.name}::{second.name}")


def _inertia(body: mujoco.MjsBody, link: d.Link) -> None:
    inertial = link.inertial
    tensor = np.array(((inertial.ixx, inertial.ixy, inertial.ixz), (inertial.ixy, inertial.iyy, inertial.iyz),
                       (inertial.ixz, inertial.iyz, inertial.izz)))
    rotation = inertial.pose.rotation()
    in_link = rotation @ tensor @ rotation.T
    body.explicitinertial = True
    body.mass = inertial.mass
    body.ipos = inertial.pose.position
    body.fullinertia = (in_link[0, 0], in_link[1, 1], in_link[2, 2], in_link[0, 1], in_link[0, 2], in_link[1, 2])


def _joint(spec: mujoco.MjSpec, body: mujoco.MjsBody, model: str, joint: d.Joint) -> None:
    kinds = {"revolute": mujoco.mjtJoint.mjJNT_HINGE, "continuous": mujoco.mjtJoint.mjJNT_HINGE,
             "prismatic": mujoco.mjtJoint.mjJNT_SLIDE, "ball": mujoco.mjtJoint.mjJNT_BALL}
    name = f"{model}::{joint.name}"
    added = body.add_joint(name=name, type=kinds[joint.type])
    added.pos = joint.pose.position
    axis = joint.pose.rotation() @ np.asarray(joint.axis.xyz)
    added.axis = axis
    added.damping = (max(joint.axis.damping, 0.0), 0.0, 0.0)  # MuJoCo 4: linear, then higher-order terms
    added.frictionloss = max(joint.axis.friction, 0.0)
    added.stiffness = (max(joint.axis.spring_stiffness, 0.0), 0.0, 0.0)
    added.springref = joint.axis.spring_reference
    if joint.type == "ball":
        added.limited = mujoco.mjtLimited.mjLIMITED_FALSE
        return
    if joint.type != "continuous" and joint.axis.limited():
        added.limited = mujoco.mjtLimited.mjLIMITED_TRUE
        added.range = (joint.axis.lower, joint.axis.upper)
    else:
        added.limited = mujoco.mjtLimited.mjLIMITED_FALSE
    drive = spec.add_actuator(name=drive_name(name), target=name, trntype=mujoco.mjtTrn.mjTRN_JOINT)
    drive.gaintype = mujoco.mjtGain.mjGAIN_FIXED
    drive.biastype = mujoco.mjtBias.mjBIAS_AFFINE
    drive.gainprm[0] = 0.0
    drive.biasprm[:3] = (0.0, 0.0, 0.0)
    drive.forcelimited = mujoco.mjtLimited.mjLIMITED_FALSE  # limited when a drive sets its max effort


def _geoms(spec: mujoco.MjSpec, body: mujoco.MjsBody, model: str, link: d.Link, load_mesh: MeshLoader) -> None:
    prefix = f"{model}::{link.name}"
    used: set[str] = set()

    def unique(name: str) -> str:
        candidate, n = name, 1
        while candidate in used:
            n += 1
            candidate = f"{name}_{n}"
        used.add(candidate)
        return candidate

    for visual in link.visuals:
        geom = _geom(spec, body, visual.geometry, visual.pose, unique(f"{prefix}::{visual.name}::visual"), load_mesh)
        geom.contype = geom.conaffinity = 0
        geom.group = VISUAL_GROUP
        geom.rgba = visual.color
        geom.mass = 0.0
    for collision in link.collisions:
        geom = _geom(spec, body, collision.geometry, collision.pose, unique(f"{prefix}::{collision.name}"), load_mesh)
        geom.group = COLLISION_GROUP
        mu = min(collision.mu, collision.mu2)
        geom.friction = (mu, 0.005, 0.0001)
        if mu <= 0:  # frictionless (a caster's mu 0): MuJoCo's friction cone of mu 0 is degenerate and
            geom.condim = 1  # its solver diverges on it; a normal-only contact is what mu 0 means
        geom.mass = 0.0
        geom.rgba = (0.5, 0.5, 0.5, 1.0)  # rays skip transparent geoms; cameras hide this group instead
    for sensor in link.sensors:
        placed = sensor_object_name(model, link.name, sensor.name)
        if sensor.type in CAMERA_TYPES:
            camera_pose = sensor.pose * OPTICAL
            camera = body.add_camera(name=placed, pos=camera_pose.position, quat=camera_pose.mj_quat())
            camera.fovy = 45.0  # set from the sensor's <horizontal_fov> and size when it renders
        elif sensor.type == "imu":
            site = body.add_site(name=placed, pos=sensor.pose.position, quat=sensor.pose.mj_quat())
            for kind, suffix in ((mujoco.mjtSensor.mjSENS_GYRO, "gyro"),
                                 (mujoco.mjtSensor.mjSENS_ACCELEROMETER, "accelerometer"),
                                 (mujoco.mjtSensor.mjSENS_FRAMEQUAT, "orientation")):
                spec.add_sensor(name=f"{placed}::{suffix}", type=kind, objtype=mujoco.mjtObj.mjOBJ_SITE,
                                objname=site.name)


def _geom(spec: mujoco.MjSpec, body: mujoco.MjsBody, geometry: d.Geometry, pose: Pose, name: str,
          load_mesh: MeshLoader) -> mujoco.MjsGeom:
    geom = body.add_geom(name=name)
    if geometry.kind == "box":
        geom.type, geom.size = mujoco.mjtGeom.mjGEOM_BOX, [v / 2 for v in geometry.size]
    elif geometry.kind == "cylinder":
        geom.type, geom.size = mujoco.mjtGeom.mjGEOM_CYLINDER, (geometry.size[0], geometry.size[1] / 2, 0.0)
    elif geometry.kind == "sphere":
        geom.type, geom.size = mujoco.mjtGeom.mjGEOM_SPHERE, (geometry.size[0], 0.0, 0.0)
    elif geometry.kind == "plane":
        geom.type = mujoco.mjtGeom.mjGEOM_PLANE
        half = [v / 2 for v in geometry.size] if len(geometry.size) == 2 else [0.0, 0.0]
        geom.size = (half[0], half[1], 1.0)
        pose = pose * plane_rotation(geometry.normal)
    else:
        vertices, faces = load_mesh(geometry)
        mesh = spec.add_mesh(name=f"{name}::mesh")
        mesh.uservert = vertices.ravel().tolist()
        mesh.userface = faces.ravel().tolist()
        mesh.scale = geometry.scale
        mesh.inertia = mujoco.mjtMeshInertia.mjMESH_INERTIA_SHELL  # open meshes have no volume
        geom.type, geom.meshname = mujoco.mjtGeom.mjGEOM_MESH, mesh.name
    geom.pos, geom.quat = pose.position, pose.mj_quat()
    return geom


def plane_rotation(normal: tuple[float, float, float]) -> Pose:
    """The rotation taking +z to `normal` (a plane's)."""
    n = np.asarray(normal, dtype=float)
    norm = float(np.linalg.norm(n))
    if not norm > 0:
        return Pose()
    n /= norm
    axis = np.cross((0.0, 0.0, 1.0), n)
    s, c = float(np.linalg.norm(axis)), float(n[2])
    if s < 1e-12:
        return Pose() if c > 0 else Pose((0.0, 0.0, 0.0), (1.0, 0.0, 0.0, 0.0))
    axis /= s
    half = math.atan2(s, c) / 2
    return Pose((0.0, 0.0, 0.0), (float(axis[0]) * math.sin(half), float(axis[1]) * math.sin(half),
                                  float(axis[2]) * math.sin(half), math.cos(half)))


def add_light(spec: mujoco.MjSpec, light: d.Light) -> None:
    kinds = {"directional": mujoco.mjtLightType.mjLIGHT_DIRECTIONAL, "spot": mujoco.mjtLightType.mjLIGHT_SPOT}
    direction = light.pose.rotation() @ np.asarray(light.direction)
    spec.worldbody.add_light(name=f"light::{light.name}", pos=light.pose.position, dir=direction,
                             type=kinds.get(light.type, mujoco.mjtLightType.mjLIGHT_POINT),
                             diffuse=light.diffuse[:3], specular=light.specular[:3],
                             castshadow=False)  # shadows would double every camera's render time


def rank_friction(spec: mujoco.MjSpec) -> None:
    """Collision priorities so that two touching surfaces take the smaller mu, as ODE does."""
    collisions = [g for g in spec.geoms if g.group == COLLISION_GROUP]
    ranks = {mu: rank for rank, mu in enumerate(sorted({g.friction[0] for g in collisions}, reverse=True))}
    for geom in collisions:
        geom.priority = ranks[geom.friction[0]]
