"""A running 3-D world on MuJoCo: Gazebo's server without ROS, no clock, no threads; a node steps it.

API (what the gazebo_ros side calls; names of links and joints are "model::link", "model::joint"):
- Making one: `World.from_sdf(text, resources)`, `World.from_file(path, resources)`, `World.empty()`;
  `Resources` says where model://, package:// and file:// lead.
- Time: `step(n=1)` advances n steps of `physics.max_step_size`; `sim_time`, `iterations`.
  `physics` (max_step_size, real_time_update_rate, real_time_factor, gravity) is read and set
  whole (`world.physics = replace(world.physics, gravity=...)`); the node paces real time by it.
- Contents: `scene` (ambient and background colours), `model_names()`, `model_description(name)`
  (links with inertia, collisions, static...), `joint_description(joint)`, `link_names(model)`,
  `joint_names(model)`, `plugins()`, `sensors()`, `visuals()` (per link: shape, size or triangles,
  local pose, colour, for a 3-D window), `lights`, `generation` (changes when a spawn or delete
  rebuilds the model). `model` and `data` are MuJoCo's.
- State: `model_state(name)`, `link_state(link)` (pose: position and quaternion xyzw; twist in the
  world frame), `model_states()` and `link_states()` (all of them, by name), `link_acceleration(link)`,
  `set_model_state(name, state)`, `set_model_twist(name, linear, angular)`, `set_link_state(link, state)`,
  `joint_state(joint)`, `set_joint_positions(model, {joint: position})`.
- Changes: `spawn_sdf(xml, name, pose)`, `spawn_urdf(xml, name, pose)`, `spawn(model)`, `delete_model(name)`
  (MjSpec edits, recompiled keeping every other model's state).
- Forces: `apply_body_wrench(link, force, torque, reference_point, start, duration)`,
  `apply_joint_effort(joint, effort, start, duration)` (start None: now; duration below 0: until
  cleared), `clear_body_wrenches(link=None)`, `clear_joint_forces(joint=None)`,
  `drive_joint(joint, velocity, max_effort)` / `release_joint(joint)` (a velocity motor with a
  torque limit, as Gazebo's Joint::SetVelocity drives wheels).
- `reset_simulation()` (poses, velocities and time to 0), `reset_world()` (poses and velocities; time goes on).
- Sensors (kame.gazebo.sensors, kame.gazebo.camera), each given a SensorInfo from `sensors()`:
  `ray_scan`, `range_reading`, `camera_frame` (RGB and/or depth, and the config with K),
  `imu_reading`, `sensor_pose`; `contacts(link)` (collisions named "model::link::collision";
  `gazebo_collision_name` gives Gazebo's name for one); noise draws from the world's seeded
  generator, so a run replays exactly.
- Trouble: every refusal is a GazeboError saying why (unknown names, NaN values, a model spawned
  inside another, bad files); a model whose state diverges (NaN or runaway speeds) is put back
  where it was spawned, at rest, and `take_warnings()` returns what happened, for the node to log.
- A World is not thread-safe: its owner (the node) calls it from one thread at a time, and renders
  cameras from one thread (an EGL context is current in one thread). `close()` frees the cameras'
  GL contexts.
- Contacts are those of the last step's collision pass; <kinematic> links are simulated as dynamic ones.
- Joint limits: an applied effort is cut to the joint's <effort>, and dropped while the joint
  turns faster than its <velocity> in the effort's direction (Gazebo's
  Joint::CheckAndTruncateForce); a drive's velocity is held within <velocity> too (Gazebo's ODE
  motor is not: there a drive past the limit gets it). A joint moved by other forces (gravity, a
  push) may exceed it, as in Gazebo.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, replace

import numpy as np

from kame.gazebo import assembly
from kame.gazebo import description as d
from kame.gazebo import sensors as sensing
from kame.gazebo.camera import CameraConfig, CameraFrame, Cameras
from kame.gazebo.engine import mujoco
from kame.gazebo.errors import GazeboError
from kame.gazebo.meshes import MeshCache
from kame.gazebo.poses import Pose, Vector3, normalized_pose
from kame.gazebo.resources import Resources, read_xml
from kame.gazebo.sdf import SdfReader
from kame.gazebo.states import JointState, SensorInfo, State, VisualShape
from kame.gazebo.urdf import UrdfReader
from kame.gazebo.xmltree import Element, parse

MAX_SPEED = 1e4  # m/s or rad/s: a body faster than this has diverged
OVERLAP = 0.05  # metres: a spawned model's collisions deeper than this inside another's are refused
MIN_RENDER_SIZE = (640, 480)  # MuJoCo's offscreen buffer, at least; larger cameras enlarge it
DRIVE_STIFFNESS = 20.0  # a drive's gain: this many times its joint's inertia a step (see _set_drive)
WARNING_CHECK_STEPS = 100
BAD_STATE = tuple(int(w) for w in (mujoco.mjtWarning.mjWARN_BADQPOS, mujoco.mjtWarning.mjWARN_BADQVEL,
                                    mujoco.mjtWarning.mjWARN_BADQACC))  # MuJoCo's own checks of NaN and huge values
FREE = int(mujoco.mjtJoint.mjJNT_FREE)
ONE_DEGREE = (int(mujoco.mjtJoint.mjJNT_HINGE), int(mujoco.mjtJoint.mjJNT_SLIDE))


@dataclass(frozen=True)
class _TimedForce:
    target: str  # link or joint
    values: tuple[float, ...]  # force, torque (world frame) and the point (link frame); or an effort
    start: float
    end: float  # math.inf: until cleared


def _finite(values: Iterable[float], what: str) -> None:
    if not all(math.isfinite(v) for v in values):
        raise GazeboError(f"{what} must be finite numbers, not NaN or infinite")


class World:
    def __init__(self, description: d.World, resources: Resources | None = None, seed: int = 0,
                 warnings: Iterable[str] = ()) -> None:
        self.name = description.name
        self.resources = resources or Resources()
        self.lights = description.lights
        self.scene = description.scene
        self.rng = np.random.default_rng(seed)
        self._world_plugins = description.plugins
        self._models: dict[str, d.Model] = {}
        self._meshes = MeshCache()
        self._warnings: list[str] = list(warnings)
        self._wrenches: list[_TimedForce] = []
        self._efforts: list[_TimedForce] = []
        self._drives: dict[str, tuple[float, float]] = {}
        self._moved_static: set[str] = set()  # static models moved since their spawn (resets put them back)
        self._forces_applied = False
        self._stale = False  # the bodies' poses lag the state after a step, until _current
        self._engine_warned: set[int] = set()  # the kinds of MuJoCo warning already passed on
        self._next_warning_check = 0
        self.iterations = 0
        self._generation = 0  # counts compilations: renderers made for an older model are remade
        self._cameras = Cameras()
        self._ray_configs: dict[int, tuple[Element, sensing.RayConfig]] = {}
        self._spec = mujoco.MjSpec()
        self._spec.compiler.degree = False
        self._spec.compiler.autolimits = False
        self._spec.compiler.boundmass = 1e-6
        self._spec.compiler.boundinertia = 1e-10
        self._spec.compiler.balanceinertia = True
        self._spec.option.integrator = mujoco.mjtIntegrator.mjINT_IMPLICITFAST
        self._spec.option.disableflags |= mujoco.mjtDisableBit.mjDSBL_AUTORESET  # divergence is ours to handle
        self._spec.visual.global_.offwidth, self._spec.visual.global_.offheight = MIN_RENDER_SIZE
        self._spec.visual.quality.offsamples = 0  # multisampling costs 8x on Mesa's software renderer (camera.py)
        self._set_spec_physics(description.physics)
        self._physics = description.physics
        self._spec.visual.headlight.ambient = description.scene.ambient[:3]  # the scene's light from everywhere
        for light in description.lights:
            try:
                assembly.add_light(self._spec, light)
            except ValueError as exc:  # MuJoCo refuses a second light of the same name as it is added
                raise GazeboError(f"{description.source}: light {light.name!r}: {exc}") from None
        for model in description.models:
            self._add_to_spec(model)
        self.model, self.data = self._compile(description.source)
        self._index()
        self._forward()

    # ------------------------------------------------------------------ making worlds

    @staticmethod
    def from_sdf(text: str | bytes, resources: Resources | None = None, source: str = "<string>",
                 seed: int = 0) -> World:
        reader = SdfReader(resources or Resources())
        description = reader.world(parse(text, source))
        return World(description, reader.resources, seed, reader.warnings)

    @staticmethod
    def from_file(path: str, resources: Resources | None = None, seed: int = 0) -> World:
        reader = SdfReader(resources or Resources())
        description = reader.world(read_xml(path))
        return World(description, reader.resources, seed, reader.warnings)

    @staticmethod
    def empty(resources: Resources | None = None, seed: int = 0) -> World:
        return World(d.World(), resources, seed)

    # ------------------------------------------------------------------ time and physics

    @property
    def sim_time(self) -> float:
        return float(self.data.time)

    @property
    def physics(self) -> d.Physics:
        return self._physics

    @physics.setter
    def physics(self, physics: d.Physics) -> None:
        _finite((physics.max_step_size, physics.real_time_update_rate, physics.real_time_factor, *physics.gravity),
                "physics properties")
        if not physics.max_step_size > 0:
            raise GazeboError(f"max_step_size must be above 0, not {physics.max_step_size}")
        if physics.real_time_update_rate < 0 or physics.real_time_factor < 0:
            raise GazeboError("real_time_update_rate and real_time_factor must be at least 0")
        self._physics = physics
        self._set_spec_physics(physics)
        self.model.opt.timestep = physics.max_step_size
        self.model.opt.gravity[:] = physics.gravity
        self._forward()  # gravity's bias forces are computed before a step

    def _set_spec_physics(self, physics: d.Physics) -> None:
        self._spec.option.timestep = physics.max_step_size
        self._spec.option.gravity = physics.gravity

    def step(self, steps: int = 1) -> None:
        """Advances `steps` steps (in one call into MuJoCo when no timed force may start or end
        between them). MuJoCo's step leaves the bodies' poses of the state it started from; they are
        brought up to date when something reads them (`_current`), not after every step."""
        if self._wrenches or self._efforts or self._forces_applied:
            for _ in range(steps):
                self._apply_forces()
                mujoco.mj_step(self.model, self.data)
                self.iterations += 1
                self._check_divergence()
        elif steps > 0:
            mujoco.mj_step(self.model, self.data, steps)
            self.iterations += steps
            self._check_divergence()
        self._stale = True
        if self.iterations >= self._next_warning_check:
            self._next_warning_check = self.iterations + WARNING_CHECK_STEPS
            self._note_engine_warnings()

    def _note_engine_warnings(self) -> None:
        """MuJoCo's own warnings (a full contact buffer, a bad position...), each kind once per
        model, for the node to log; a bad state among them is a divergence."""
        warnings = self.data.warning
        if any(warnings[kind].number for kind in BAD_STATE):
            self._check_divergence(engine_said_so=True)
        for kind, warning in enumerate(warnings):
            if warning.number and kind not in self._engine_warned:
                self._engine_warned.add(kind)
                text = mujoco.mju_warningText(kind, warning.lastinfo)
                self._warnings.append(f"MuJoCo warns at sim time {self.sim_time:.3f} s: {text}")

    def _forward(self) -> None:
        """Everything MuJoCo derives from the state (after the state or the model changed)."""
        mujoco.mj_forward(self.model, self.data)
        self._stale = False

    def _current(self) -> None:
        """Poses, twists and cameras of the state reached (the kinematic half of mj_forward)."""
        if self._stale:
            mujoco.mj_kinematics(self.model, self.data)
            mujoco.mj_comPos(self.model, self.data)
            mujoco.mj_camlight(self.model, self.data)
            mujoco.mj_comVel(self.model, self.data)
            self._stale = False

    # ------------------------------------------------------------------ contents

    def model_names(self) -> list[str]:
        return list(self._models)

    def model_description(self, name: str) -> d.Model:
        return self._model(name)

    def link_names(self, model: str) -> list[str]:
        return [f"{model}::{link.name}" for link in self._model(model).links]

    def joint_names(self, model: str) -> list[str]:
        return [f"{model}::{joint.name}" for joint in self._model(model).joints]

    def joint_description(self, joint: str) -> d.Joint:
        model, _, local = joint.partition("::")
        found = next((j for j in self._model(model).joints if j.name == local), None)
        if found is None:
            raise GazeboError(f"no joint named {joint!r}")
        return found

    def plugins(self) -> list[d.Plugin]:
        return [*self._world_plugins, *(p for m in self._models.values() for p in m.plugins)]

    def sensors(self) -> list[SensorInfo]:
        return [SensorInfo(m.name, f"{m.name}::{link.name}", s.name, s.type, s.pose, s.update_rate, s.always_on,
                           s.visualize, s.element)
                for m in self._models.values() for link in m.links for s in link.sensors]

    def visuals(self) -> list[VisualShape]:
        shapes = []
        for m in self._models.values():
            for link in m.links:
                for v in link.visuals:
                    triangles = self._meshes.triangles(v.geometry) if v.geometry.kind == "mesh" else None
                    # a plane is drawn in its pose's x-y plane, turned to face its normal
                    pose = v.pose * assembly.plane_rotation(v.geometry.normal) if v.geometry.kind == "plane" else v.pose
                    shapes.append(VisualShape(f"{m.name}::{link.name}", v.name, v.geometry.kind, v.geometry.size,
                                              triangles, pose, v.color))
        return shapes

    def take_warnings(self) -> list[str]:
        """What was left out or put right since the last call (for the node to log), oldest first."""
        taken, self._warnings = self._warnings, []
        return taken

    @property
    def generation(self) -> int:
        """Changes each time the MuJoCo model is rebuilt (a spawn or a delete)."""
        return self._generation

    # ------------------------------------------------------------------ state

    def body_id(self, link: str) -> int:
        found = mujoco.mj_name2id(self.model, mujoco.mjtObj.mjOBJ_BODY, link)
        if found < 0:
            raise GazeboError(f"no link named {link!r} (links are named model::link)")
        return int(found)

    def link_state(self, link: str) -> State:
        body = self.body_id(link)
        self._current()
        twist = np.zeros(6)
        mujoco.mj_objectVelocity(self.model, self.data, mujoco.mjtObj.mjOBJ_BODY, body, twist, 0)
        return State(Pose.from_mj(self.data.xpos[body], self.data.xquat[body]),
                     (float(twist[3]), float(twist[4]), float(twist[5])),
                     (float(twist[0]), float(twist[1]), float(twist[2])))

    def link_acceleration(self, link: str) -> tuple[Vector3, Vector3]:
        """The link's linear and angular acceleration at its origin in the world frame, the linear
        one as an accelerometer feels it (gravity's reaction included: +9.8 upward at rest), for the
        plugins that read a body's acceleration (gazebo_ros_imu as a model plugin)."""
        body = self.body_id(link)
        self._current()
        mujoco.mj_rnePostConstraint(self.model, self.data)  # the bodies' accelerations, contact forces included
        acceleration = np.zeros(6)
        mujoco.mj_objectAcceleration(self.model, self.data, mujoco.mjtObj.mjOBJ_BODY, body, acceleration, 0)
        return ((float(acceleration[3]), float(acceleration[4]), float(acceleration[5])),
                (float(acceleration[0]), float(acceleration[1]), float(acceleration[2])))

    def link_states(self) -> dict[str, State]:
        """Every link's state, by "model::link" (for /gazebo/link_states and a 3-D window's frames)."""
        self._current()
        twist = np.zeros(6)
        states = {}
        for body in range(1, self.model.nbody):
            mujoco.mj_objectVelocity(self.model, self.data, mujoco.mjtObj.mjOBJ_BODY, body, twist, 0)
            states[self._body_names[body]] = State(Pose.from_mj(self.data.xpos[body], self.data.xquat[body]),
                                                   (float(twist[3]), float(twist[4]), float(twist[5])),
                                                   (float(twist[0]), float(twist[1]), float(twist[2])))
        return states

    def model_states(self) -> dict[str, State]:
        """Every model's state, by name (for /gazebo/model_states)."""
        return {name: self.model_state(name) for name in self._models}

    def model_state(self, name: str) -> State:
        """The model frame's pose (its canonical, first, link's pose less that link's pose in the
        model) and the canonical link's twist, as Gazebo reports a model's."""
        model = self._model(name)
        if not model.links:
            return State(model.pose)
        canonical = model.links[0]
        state = self.link_state(f"{name}::{canonical.name}")
        return replace(state, pose=state.pose * canonical.pose.inverse())

    def set_model_state(self, name: str, state: State) -> None:
        """Moves the whole model rigidly (its joints keep their positions) and gives each of its free
        links the twist; a static model moves too."""
        self._check_state(state, f"the state of model {name!r}")
        model = self._model(name)
        target = normalized_pose(state.pose)
        move = target * self.model_state(name).pose.inverse()
        for link in model.links:
            body = self.body_id(f"{name}::{link.name}")
            if self.model.body_parentid[body] != 0:
                continue
            current = Pose.from_mj(self.data.xpos[body], self.data.xquat[body])
            self._place_root(body, move * current, state)
        if model.static:
            self._moved_static.add(name)
        self._forward()

    def set_model_twist(self, name: str, linear: Vector3, angular: Vector3) -> None:
        """Gives the model's free links this twist (world frame) where they are, as planar_move
        drives a model each update."""
        _finite((*linear, *angular), f"the twist of model {name!r}")
        self._current()
        for link in self._model(name).links:
            body = self.body_id(f"{name}::{link.name}")
            joint = self.model.body_jntadr[body]
            if self.model.body_parentid[body] == 0 and joint >= 0 and int(self.model.jnt_type[joint]) == FREE:
                dof = self.model.jnt_dofadr[joint]
                self.data.qvel[dof:dof + 3] = linear
                rotation = self.data.xmat[body].reshape(3, 3)
                self.data.qvel[dof + 3:dof + 6] = rotation.T @ np.asarray(angular)  # MuJoCo's are local
        self._forward()

    def set_link_state(self, link: str, state: State) -> None:
        """Moves a link that hangs on nothing but the world (a free or static link); a link on a joint
        is moved through its model or its joint."""
        self._check_state(state, f"the state of link {link!r}")
        body = self.body_id(link)
        if self.model.body_parentid[body] != 0:
            raise GazeboError(f"link {link!r} hangs on a joint of its model: set the model's state or the joint's "
                              f"position instead")
        self._place_root(body, normalized_pose(state.pose), state)
        if self._model(link.partition("::")[0]).static:
            self._moved_static.add(link.partition("::")[0])
        self._forward()

    def _place_root(self, body: int, pose: Pose, state: State) -> None:
        joint = self.model.body_jntadr[body]
        if joint < 0 or int(self.model.jnt_type[joint]) != FREE:
            self.model.body_pos[body] = pose.position
            self.model.body_quat[body] = pose.mj_quat()
            spec_body = self._spec.body(mujoco.mj_id2name(self.model, mujoco.mjtObj.mjOBJ_BODY, body))
            spec_body.pos, spec_body.quat = pose.position, pose.mj_quat()
            return
        qpos, dof = self.model.jnt_qposadr[joint], self.model.jnt_dofadr[joint]
        self.data.qpos[qpos:qpos + 3] = pose.position
        self.data.qpos[qpos + 3:qpos + 7] = pose.mj_quat()
        self.data.qvel[dof:dof + 3] = state.linear
        self.data.qvel[dof + 3:dof + 6] = pose.rotation().T @ np.asarray(state.angular)  # MuJoCo's are local

    def _check_state(self, state: State, what: str) -> None:
        _finite((*state.pose.position, *state.pose.orientation, *state.linear, *state.angular), what)

    def joint_state(self, joint: str) -> JointState:
        jid = self._joint_id(joint)
        qpos, dof = self.model.jnt_qposadr[jid], self.model.jnt_dofadr[jid]
        width = {int(mujoco.mjtJoint.mjJNT_BALL): (4, 3)}.get(int(self.model.jnt_type[jid]), (1, 1))
        return JointState(tuple(float(v) for v in self.data.qpos[qpos:qpos + width[0]]),
                          tuple(float(v) for v in self.data.qvel[dof:dof + width[1]]))

    def set_joint_positions(self, model: str, positions: Mapping[str, float]) -> None:
        """Sets one-degree joints' positions (spawn_model -J, set_model_configuration), at rest."""
        _finite(positions.values(), "joint positions")
        for name, position in positions.items():
            jid = self._joint_id(f"{model}::{name}")
            self.data.qpos[self.model.jnt_qposadr[jid]] = position
            self.data.qvel[self.model.jnt_dofadr[jid]] = 0.0
        self._forward()

    def _joint_id(self, joint: str, one_degree: bool = False) -> int:
        jid = mujoco.mj_name2id(self.model, mujoco.mjtObj.mjOBJ_JOINT, joint)
        if jid < 0:
            raise GazeboError(f"no joint named {joint!r} (joints are named model::joint; fixed joints have no state)")
        if one_degree and int(self.model.jnt_type[jid]) not in ONE_DEGREE:
            raise GazeboError(f"joint {joint!r} is not a revolute, continuous or prismatic joint")
        return int(jid)

    # ------------------------------------------------------------------ spawning and deleting

    def spawn_sdf(self, xml: str | bytes, name: str = "", pose: Pose | None = None,
                  source: str = "<string>") -> str:
        reader = SdfReader(self.resources)
        model = reader.model_document(parse(xml, source), name)
        self._warnings += reader.warnings
        return self.spawn(model if pose is None else replace(model, pose=pose))

    def spawn_urdf(self, xml: str | bytes, name: str = "", pose: Pose | None = None,
                   source: str = "<string>") -> str:
        reader = UrdfReader(self.resources)
        model = reader.model(parse(xml, source), name)
        self._warnings += reader.warnings
        return self.spawn(model if pose is None else replace(model, pose=pose))

    def spawn(self, model: d.Model) -> str:
        """Adds `model` to the running world; the others keep their state. Refused (GazeboError, the
        world unchanged) when the name is taken, the model is wrong, or it would be inside another."""
        if model.name in self._models:
            raise GazeboError(f"a model named {model.name!r} already exists; delete it or choose another name")
        if "::" in model.name or not model.name:
            raise GazeboError(f"{model.name!r} cannot name a model (it must be non-empty and without '::')")
        self._check_state(State(model.pose), f"the pose of model {model.name!r}")
        model = replace(model, pose=normalized_pose(model.pose))
        try:
            self._add_to_spec(model)
            self.model, self.data = self._recompile(model.source or "<string>")
        except GazeboError:
            self._remove_from_spec(model.name)
            self._models.pop(model.name, None)
            raise
        self._index()
        self._forward()
        inside = self._overlapped_by(model.name)
        if inside:
            self.delete_model(model.name)
            raise GazeboError(f"model {model.name!r} would be inside model {inside[0]!r} ({inside[1]:.3f} m deep); "
                              f"spawn it elsewhere")
        return model.name

    def delete_model(self, name: str) -> None:
        self._model(name)
        self._remove_from_spec(name)
        del self._models[name]
        prefix = f"{name}::"
        self._wrenches = [w for w in self._wrenches if not w.target.startswith(prefix)]
        self._efforts = [e for e in self._efforts if not e.target.startswith(prefix)]
        self._drives = {j: v for j, v in self._drives.items() if not j.startswith(prefix)}
        self._ray_configs.clear()  # the deleted model's sensors' among them
        self._moved_static.discard(name)
        self.model, self.data = self._recompile(name)
        self._index()
        self._forward()

    def _add_to_spec(self, model: d.Model) -> None:
        self._models[model.name] = model
        for link in model.links:
            for sensor in link.sensors:
                self._grow_render_buffer(sensor)
        try:
            assembly.add_model(self._spec, model, self._meshes.load, self._warnings)
        except GazeboError:
            raise
        except ValueError as exc:  # MuJoCo refuses some things as they are added (a repeated name)
            raise GazeboError(f"{model.source}: model {model.name!r}: {exc}") from None

    def _remove_from_spec(self, name: str) -> None:
        prefix = f"{name}::"
        for actuator in [a for a in self._spec.actuators if a.name.startswith(prefix)]:
            self._spec.delete(actuator)
        for sensor in [s for s in self._spec.sensors if s.name.startswith(prefix)]:
            self._spec.delete(sensor)
        for exclusion in [e for e in self._spec.excludes if e.name.startswith(prefix)]:
            self._spec.delete(exclusion)
        for body in [b for b in self._spec.worldbody.bodies if b.name.startswith(prefix)]:
            self._spec.delete(body)
        for mesh in [m for m in self._spec.meshes if m.name.startswith(prefix)]:
            self._spec.delete(mesh)

    def _grow_render_buffer(self, sensor: d.Sensor) -> None:
        """MuJoCo's offscreen buffer as large as the largest camera; a camera's bad configuration is
        refused here, as its model is loaded."""
        if sensor.type not in assembly.CAMERA_TYPES:
            return
        config = CameraConfig.of(sensor.element)
        global_ = self._spec.visual.global_
        global_.offwidth, global_.offheight = max(global_.offwidth, config.width), max(global_.offheight, config.height)

    def _compile(self, source: str) -> tuple[mujoco.MjModel, mujoco.MjData]:
        assembly.rank_friction(self._spec)
        try:
            model = self._spec.compile()
        except ValueError as exc:
            raise GazeboError(f"{source}: MuJoCo cannot build the world: {exc}") from None
        self._generation += 1
        return model, mujoco.MjData(model)

    def _recompile(self, source: str) -> tuple[mujoco.MjModel, mujoco.MjData]:
        assembly.rank_friction(self._spec)
        try:
            model, data = self._spec.recompile(self.model, self.data)
        except ValueError as exc:
            raise GazeboError(f"{source}: MuJoCo cannot build the model: {exc}") from None
        self._generation += 1
        self._engine_warned.clear()  # a new MjData counts from 0
        self.model, self.data = model, data
        self.physics = self._physics  # the runtime settings live in the compiled model: give them again
        for joint, (velocity, max_effort) in self._drives.items():
            self._set_drive(joint, velocity, max_effort)
        return model, data

    def _index(self) -> None:
        """Each body's name and the model it belongs to (by the names assembly gives)."""
        self._body_names = [mujoco.mj_id2name(self.model, mujoco.mjtObj.mjOBJ_BODY, body) or ""
                            for body in range(self.model.nbody)]
        self._body_model = [name.partition("::")[0] for name in self._body_names]

    def _overlapped_by(self, name: str) -> tuple[str, float] | None:
        for contact in self.data.contact[:self.data.ncon]:
            models = (self._body_model[self.model.geom_bodyid[contact.geom1]],
                      self._body_model[self.model.geom_bodyid[contact.geom2]])
            if name in models and models[0] != models[1] and contact.dist < -OVERLAP:
                return (models[1] if models[0] == name else models[0]) or "the world", -float(contact.dist)
        return None

    def _model(self, name: str) -> d.Model:
        if name not in self._models:
            raise GazeboError(f"no model named {name!r}")
        return self._models[name]

    # ------------------------------------------------------------------ forces

    def apply_body_wrench(self, link: str, force: Vector3, torque: Vector3 = (0.0, 0.0, 0.0),
                          reference_point: Vector3 = (0.0, 0.0, 0.0), start: float | None = None,
                          duration: float = -1.0) -> None:
        """`force` and `torque` (world frame) at `reference_point` (the link's frame), from sim time
        `start` (None: now) for `duration` seconds (below 0: until cleared; 0: not at all)."""
        _finite((*force, *torque, *reference_point, duration, *(() if start is None else (start,))),
                f"the wrench on {link!r}")
        self.body_id(link)
        begin = self.sim_time if start is None else start
        end = math.inf if duration < 0 else begin + duration
        self._wrenches.append(_TimedForce(link, (*force, *torque, *reference_point), begin, end))

    def apply_joint_effort(self, joint: str, effort: float, start: float | None = None,
                           duration: float = -1.0) -> None:
        """A torque (revolute) or force (prismatic), limited to the joint's <effort> as Gazebo limits it."""
        _finite((effort, duration, *(() if start is None else (start,))), f"the effort on {joint!r}")
        self._joint_id(joint, one_degree=True)
        begin = self.sim_time if start is None else start
        end = math.inf if duration < 0 else begin + duration
        self._efforts.append(_TimedForce(joint, (effort,), begin, end))

    def clear_body_wrenches(self, link: str | None = None) -> None:
        self._wrenches = [w for w in self._wrenches if link is not None and w.target != link]

    def clear_joint_forces(self, joint: str | None = None) -> None:
        self._efforts = [e for e in self._efforts if joint is not None and e.target != joint]

    def drive_joint(self, joint: str, velocity: float, max_effort: float) -> None:
        """Holds `joint` at `velocity` with at most `max_effort` (a wheel of diff_drive)."""
        _finite((velocity, max_effort), f"the drive of {joint!r}")
        if max_effort < 0:
            raise GazeboError(f"the drive of {joint!r} needs a max effort of at least 0, not {max_effort}")
        self._set_drive(joint, velocity, max_effort)
        self._drives[joint] = (velocity, max_effort)

    def release_joint(self, joint: str) -> None:
        self._drives.pop(joint, None)
        self._set_drive(joint, 0.0, 0.0)

    def _set_drive(self, joint: str, velocity: float, max_effort: float) -> None:
        jid = self._joint_id(joint, one_degree=True)
        actuator = mujoco.mj_name2id(self.model, mujoco.mjtObj.mjOBJ_ACTUATOR, assembly.drive_name(joint))
        # scaled by the joint's own inertia: 20x a step follows a pair of wheels' arc within 1 %
        # (tests/gazebo/test_physics.py); a hundred times stiffer, the servo fights the soft contacts
        # it drives through and the wheels chatter and slip, ten times softer it lags
        inertia = float(self.model.dof_M0[self.model.jnt_dofadr[jid]])
        gain = DRIVE_STIFFNESS * inertia / self.physics.max_step_size if max_effort > 0 else 0.0
        limit = self.joint_description(joint).axis.velocity
        if limit >= 0:
            velocity = max(-limit, min(limit, velocity))
        self.model.actuator_gainprm[actuator, 0] = gain
        self.model.actuator_biasprm[actuator, 2] = -gain
        self.model.actuator_forcelimited[actuator] = 1
        self.model.actuator_forcerange[actuator] = (-max_effort, max_effort)
        self.data.ctrl[actuator] = velocity

    def _apply_forces(self) -> None:
        if not self._wrenches and not self._efforts:
            if self._forces_applied:
                self.data.xfrc_applied[:] = 0.0
                self.data.qfrc_applied[:] = 0.0
                self._forces_applied = False
            return
        now = self.sim_time
        self._current()  # a wrench's point is placed on the body where it is now
        self.data.xfrc_applied[:] = 0.0
        self.data.qfrc_applied[:] = 0.0
        for wrench in self._wrenches:
            if wrench.start <= now < wrench.end:
                body = self.body_id(wrench.target)
                force, torque, point = (np.asarray(wrench.values[i:i + 3]) for i in (0, 3, 6))
                at = self.data.xpos[body] + self.data.xmat[body].reshape(3, 3) @ point
                self.data.xfrc_applied[body, :3] += force
                self.data.xfrc_applied[body, 3:] += torque + np.cross(at - self.data.xipos[body], force)
        for effort in self._efforts:
            if effort.start <= now < effort.end:
                dof = self.model.jnt_dofadr[self._joint_id(effort.target)]
                axis = self.joint_description(effort.target).axis
                value = effort.values[0] if axis.effort < 0 else max(-axis.effort, min(axis.effort, effort.values[0]))
                speed = self.data.qvel[dof]
                if axis.velocity >= 0 and ((speed > axis.velocity and value > 0) or
                                           (speed < -axis.velocity and value < 0)):
                    value = 0.0  # past its velocity limit, no effort drives it further
                self.data.qfrc_applied[dof] += value
        self._wrenches = [w for w in self._wrenches if w.end > now]
        self._efforts = [e for e in self._efforts if e.end > now]
        self._forces_applied = True

    # ------------------------------------------------------------------ sensors

    def sensor_pose(self, sensor: SensorInfo) -> Pose:
        """The sensor's pose in the world."""
        return self.link_state(sensor.link).pose * sensor.pose

    def ray_scan(self, sensor: SensorInfo) -> sensing.RayScan:
        self._current()
        # a sensor's configuration is read once: the element is kept with it, so its id is not reused
        known = self._ray_configs.get(id(sensor.config))
        if known is None or known[0] is not sensor.config:
            known = self._ray_configs[id(sensor.config)] = (sensor.config, sensing.RayConfig.of(sensor.config))
        config = known[1]
        return sensing.ray_scan(self.model, self.data, self.sensor_pose(sensor), self.body_id(sensor.link), config,
                                self.rng)

    def range_reading(self, sensor: SensorInfo) -> sensing.RangeReading:
        """A sonar's reading, or the nearest of a ray sensor's rays (gazebo_ros_range)."""
        sonar = sensor.config.child("sonar")
        self._current()
        if sonar is not None:
            return sensing.sonar_range(self.model, self.data, self.sensor_pose(sensor), self.body_id(sensor.link),
                                       sonar, self.rng)
        return sensing.ray_range(self.ray_scan(sensor))

    def camera_frame(self, sensor: SensorInfo, rgb: bool = True, depth: bool = False) -> CameraFrame:
        if sensor.type not in assembly.CAMERA_TYPES:
            raise GazeboError(f"sensor {sensor.name!r} of {sensor.link!r} is a {sensor.type} sensor, not a camera")
        name = assembly.sensor_object_name(sensor.model, sensor.link.partition("::")[2], sensor.name)
        self._current()
        return self._cameras.render(self.model, self.data, self._generation, name, CameraConfig.of(sensor.config),
                                    rgb, depth, self.rng, self.scene.background)

    def imu_reading(self, sensor: SensorInfo) -> sensing.ImuReading:
        name = assembly.sensor_object_name(sensor.model, sensor.link.partition("::")[2], sensor.name)
        return sensing.imu_reading(self.model, self.data, name, sensor.config, self.rng)

    def contacts(self, link: str) -> list[sensing.Contact]:
        return sensing.contacts(self.model, self.data, self.body_id(link))

    def gazebo_collision_name(self, collision: str) -> str:
        """A collision's "model::link::collision" as Gazebo names it (a URDF's lumped links and
        collisions renamed, as in Gazebo's contact messages); other names are returned as they are."""
        model, _, rest = collision.partition("::")
        link, _, name = rest.rpartition("::")
        found = self._models[model].link(link) if model in self._models else None
        match = next((c for c in found.collisions if c.name == name), None) if found is not None else None
        return f"{model}::{match.gazebo_name}" if match is not None and match.gazebo_name else collision

    def close(self) -> None:
        """Frees the cameras' GL contexts (the world itself holds no other resource)."""
        self._cameras.close()

    # ------------------------------------------------------------------ resets and divergence

    def reset_world(self) -> None:
        """Every model back where it was spawned, at rest; sim time goes on."""
        time = self.data.time
        self._reset()
        self.data.time = time

    def reset_simulation(self) -> None:
        """reset_world, and sim time and iterations back to 0."""
        self._reset()
        self.iterations = 0

    def _reset(self) -> None:
        mujoco.mj_resetData(self.model, self.data)
        for name in self._moved_static:  # a static model's place is in the compiled model, not the state
            for link in self._models[name].links:
                body = self.body_id(f"{name}::{link.name}")
                if self.model.body_parentid[body] == 0:  # the others hang on these
                    pose = self._models[name].pose * link.pose
                    self._place_root(body, pose, State(pose))
        self._moved_static.clear()
        self._wrenches.clear()
        self._efforts.clear()
        for joint, (velocity, max_effort) in self._drives.items():
            self._set_drive(joint, velocity, max_effort)
        self._forward()

    def _check_divergence(self, engine_said_so: bool = False) -> None:
        qvel = self.data.qvel
        # one dot product a step: NaN and infinities make it NaN, a runaway speed makes it large;
        # MuJoCo's own count of NaN positions and huge accelerations is read every
        # WARNING_CHECK_STEPS (reading its warnings costs more than the step of a small world)
        if float(qvel @ qvel) < MAX_SPEED * MAX_SPEED and not engine_said_so:
            return
        bad_dofs = set(np.flatnonzero(~np.isfinite(qvel) | (np.abs(np.nan_to_num(qvel, nan=np.inf)) >= MAX_SPEED)))
        bad_qpos = set(np.flatnonzero(~np.isfinite(self.data.qpos)))
        for kind in BAD_STATE:  # reported below as the divergence they are; lastinfo is the index MuJoCo met
            warning = self.data.warning[kind]
            if warning.number and 0 <= warning.lastinfo < (self.model.nq if kind == BAD_STATE[0] else self.model.nv):
                (bad_qpos if kind == BAD_STATE[0] else bad_dofs).add(warning.lastinfo)
            warning.number = 0
        bad_models = {self._body_model[self.model.dof_bodyid[dof]] for dof in bad_dofs}
        for joint in range(self.model.njnt):
            start, width = self.model.jnt_qposadr[joint], {0: 7, 1: 4}.get(int(self.model.jnt_type[joint]), 1)
            if any(start <= q < start + width for q in bad_qpos):
                bad_models.add(self._body_model[self.model.jnt_bodyid[joint]])
        for joint in range(self.model.njnt):
            if self._body_model[self.model.jnt_bodyid[joint]] in bad_models:
                start, dof = self.model.jnt_qposadr[joint], self.model.jnt_dofadr[joint]
                positions, speeds = {0: (7, 6), 1: (4, 3)}.get(int(self.model.jnt_type[joint]), (1, 1))
                self.data.qpos[start:start + positions] = self.model.qpos0[start:start + positions]
                self.data.qvel[dof:dof + speeds] = 0.0
        self.data.qacc_warmstart[:] = 0.0
        # the forces that drove it there would only do it again
        self._wrenches = [w for w in self._wrenches if w.target.partition("::")[0] not in bad_models]
        self._efforts = [e for e in self._efforts if e.target.partition("::")[0] not in bad_models]
        names = ", ".join(sorted(m or "the world" for m in bad_models))
        self._warnings.append(f"model {names} diverged at sim time {self.sim_time:.3f} s (NaN or speeds over "
                              f"{MAX_SPEED:g}): put back where it was spawned, at rest, its applied forces cleared")
        self._forward()
