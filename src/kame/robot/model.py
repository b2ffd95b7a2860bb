"""A URDF's kinematic tree, as robot_state_publisher and joint_state_publisher use it.

Rules (robot_state_publisher and kdl_parser, joint_state_publisher):
- The URDF is parsed by urdf_parser_py (the module ROS's Python tools parse URDF with), then
  checked as urdfdom checks it before kdl_parser builds the tree (`tree_problem`): every joint's
  links exist, no link has two parent joints, exactly one link has none (the root), and every
  link hangs from it. A joint loop is refused naming its joints: published, it was a tf loop.
- fixed joints, and floating and planar ones (kdl_parser turns those into fixed joints), make
  the static transforms; revolute, continuous and prismatic joints move.
- A moving joint's transform is its origin followed by a rotation about (or a translation
  along) its axis by the position; the axis defaults to (1, 0, 0) and is normalised.
- A mimic joint's position is multiplier * (the joint it mimics) + offset.
- joint_state_publisher's free joints are the moving joints that mimic nothing; a continuous
  joint ranges over [-pi, pi]; a joint starts at 0, or at the middle of its range when 0 is
  outside it, or at the value the `zeros` parameter gives.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass

from kame.tf import rotation
from kame.tf.rotation import Quaternion, Vector

FIXED_KINDS = ("fixed", "floating", "planar")
MOVING_KINDS = ("revolute", "continuous", "prismatic")

Transform = tuple[str, str, Vector, Quaternion]  # parent, child, translation, rotation


def rpy_quaternion(roll: float, pitch: float, yaw: float) -> Quaternion:
    """URDF's rpy (fixed axes x, y, z) as a quaternion (x, y, z, w)."""
    cr, sr = math.cos(roll / 2), math.sin(roll / 2)
    cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
    cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
    return (sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy, cr * cp * sy - sr * sp * cy,
            cr * cp * cy + sr * sp * sy)


@dataclass(frozen=True)
class Joint:
    name: str
    kind: str
    parent: str
    child: str
    translation: Vector
    rotation: Quaternion
    axis: Vector
    lower: float
    upper: float
    mimic: tuple[str, float, float] | None  # (joint, multiplier, offset)

    def transform(self, position: float = 0.0) -> Transform:
        """The child's frame in the parent's at `position` (ignored by a fixed joint)."""
        if self.kind not in MOVING_KINDS or position == 0.0:
            return self.parent, self.child, self.translation, self.rotation
        if self.kind == "prismatic":
            motion_t: Vector = (self.axis[0] * position, self.axis[1] * position, self.axis[2] * position)
            motion_q: Quaternion = rotation.IDENTITY
        else:
            s = math.sin(position / 2)
            motion_t, motion_q = rotation.ZERO, (self.axis[0] * s, self.axis[1] * s, self.axis[2] * s,
                                                 math.cos(position / 2))
        translation, quaternion = rotation.chain(self.rotation, self.translation, motion_q, motion_t)
        return self.parent, self.child, translation, quaternion


def _vector(values: object, default: Vector) -> Vector:
    if not isinstance(values, (list, tuple)) or len(values) != 3:
        return default
    return float(values[0]), float(values[1]), float(values[2])


class RobotTree:
    """The joints of one URDF document; ValueError when the text is not a URDF."""

    def __init__(self, text: str) -> None:
        from urdf_parser_py.urdf import URDF

        try:
            robot = URDF.from_xml_string(text.encode() if isinstance(text, str) else text)
        except Exception as exc:  # lxml's and urdf_parser_py's own errors
            raise ValueError(f"cannot parse the robot description: {exc}") from None
        self.name = str(robot.name or "")
        self.links = [str(link.name) for link in robot.links]
        self.joints: list[Joint] = []
        for joint in robot.joints:
            origin = joint.origin
            translation = _vector(origin.xyz if origin is not None else None, rotation.ZERO)
            roll, pitch, yaw = _vector(origin.rpy if origin is not None else None, rotation.ZERO)
            axis = _vector(joint.axis, (1.0, 0.0, 0.0))
            length = math.sqrt(sum(a * a for a in axis)) or 1.0
            limit = joint.limit
            lower = float(limit.lower) if limit is not None and limit.lower is not None else 0.0
            upper = float(limit.upper) if limit is not None and limit.upper is not None else 0.0
            if joint.type == "continuous":
                lower, upper = -math.pi, math.pi
            mimic = None
            if joint.mimic is not None:
                mimic = (str(joint.mimic.joint), float(joint.mimic.multiplier if joint.mimic.multiplier is not None
                                                       else 1.0), float(joint.mimic.offset or 0.0))
            self.joints.append(Joint(str(joint.name), str(joint.type), str(joint.parent), str(joint.child),
                                     translation, rpy_quaternion(roll, pitch, yaw),
                                     (axis[0] / length, axis[1] / length, axis[2] / length), lower, upper, mimic))
        problem = tree_problem(self.links, self.joints)
        if problem:
            raise ValueError(problem)
        self.by_name = {joint.name: joint for joint in self.joints}

    @property
    def fixed(self) -> list[Joint]:
        return [joint for joint in self.joints if joint.kind in FIXED_KINDS]

    @property
    def moving(self) -> list[Joint]:
        return [joint for joint in self.joints if joint.kind in MOVING_KINDS]

    def static_transforms(self) -> list[Transform]:
        return [joint.transform() for joint in self.fixed]

    def moving_transforms(self, positions: Mapping[str, float]) -> list[Transform]:
        """The transforms of the moving joints `positions` names, and of the mimic joints whose
        joint it names (robot_state_publisher publishes no joint it was told nothing of)."""
        out = []
        for joint in self.moving:
            if joint.name in positions:
                out.append(joint.transform(positions[joint.name]))
            elif joint.mimic is not None and joint.mimic[0] in positions:
                out.append(joint.transform(positions[joint.mimic[0]] * joint.mimic[1] + joint.mimic[2]))
        return out


def tree_problem(links: list[str], joints: list[Joint]) -> str | None:
    """Why `joints` do not make `links` a tree with one root, or None when they do. The wording
    is urdf_parser_py's and urdfdom's, with the links and joints named."""
    defined = set(links)
    parent_joint: dict[str, Joint] = {}
    for joint in joints:
        for role, link in (("parent", joint.parent), ("child", joint.child)):
            if link not in defined:
                return f"{role} link [{link}] of joint [{joint.name}] not found"
        other = parent_joint.get(joint.child)
        if other is not None:
            return (f"link [{joint.child}] is the child of two joints, [{other.name}] and [{joint.name}]: "
                    "invalid URDF, a robot is a tree")
        parent_joint[joint.child] = joint
    roots = [link for link in links if link not in parent_joint]
    if len(roots) > 1:
        return f"Multiple roots detected, invalid URDF: links [{'], ['.join(roots)}] have no parent joint"
    loop = _joint_loop(links, parent_joint, roots)
    if loop and not roots:
        return f"No roots detected, invalid URDF: every link has a parent joint, and joints {loop} form a loop"
    if loop:
        return f"joints {loop} form a loop, invalid URDF: a robot is a tree from its root [{roots[0]}]"
    return None


def _joint_loop(links: list[str], parent_joint: Mapping[str, Joint], roots: list[str]) -> str | None:
    """The joints of a loop, as `[a] -> [b] -> [c]` (each the parent of the next's link), when a
    link does not hang from the root; None when every link does."""
    below_root = set(roots)
    for start in links:
        path: list[str] = []
        link = start
        while link not in below_root and link not in path:
            path.append(link)
            link = parent_joint[link].parent
        if link in below_root:
            below_root.update(path)
            continue
        cycle = path[path.index(link):]  # child links, each found from the one before it
        return " -> ".join(f"[{parent_joint[child].name}]" for child in reversed(cycle))
    return None


@dataclass
class FreeJoint:
    name: str
    lower: float
    upper: float
    zero: float
    position: float


class JointPositions:
    """joint_state_publisher's model: a position for each free joint (what its sliders set),
    and the positions of every moving joint, mimic joints following theirs."""

    SLIDER_STEPS = 10000  # the slider's integer range, as joint_state_publisher_gui's

    def __init__(self, tree: RobotTree, zeros: Mapping[str, float] | None = None) -> None:
        self.tree = tree
        self.free: dict[str, FreeJoint] = {}
        for joint in tree.moving:
            if joint.mimic is not None:
                continue
            zero = 0.0 if joint.lower <= 0.0 <= joint.upper or joint.lower == joint.upper else (
                (joint.lower + joint.upper) / 2)
            if zeros and joint.name in zeros:
                zero = float(zeros[joint.name])
            self.free[joint.name] = FreeJoint(joint.name, joint.lower, joint.upper, zero, zero)

    def set(self, name: str, position: float) -> None:
        joint = self.free[name]
        joint.position = min(max(position, joint.lower), joint.upper) if joint.lower < joint.upper else position

    def center(self) -> None:
        for joint in self.free.values():
            joint.position = joint.zero

    def randomize(self, draw: Callable[[float, float], float]) -> None:
        """Each free joint to `draw(lower, upper)` (random.uniform in the window)."""
        for joint in self.free.values():
            joint.position = draw(joint.lower, joint.upper)

    def update(self, names: list[str], positions: list[float]) -> None:
        """Positions from another JointState (joint_state_publisher's source_list)."""
        for name, position in zip(names, positions, strict=False):
            if name in self.free:
                self.free[name].position = float(position)

    def names_and_positions(self) -> tuple[list[str], list[float]]:
        names, positions = [], []
        for joint in self.tree.moving:
            if joint.name in self.free:
                position = self.free[joint.name].position
            elif joint.mimic is not None and joint.mimic[0] in self.free:
                position = self.free[joint.mimic[0]].position * joint.mimic[1] + joint.mimic[2]
            else:
                continue
            names.append(joint.name)
            positions.append(position)
        return names, positions

    def slider_value(self, name: str) -> int:
        joint = self.free[name]
        span = joint.upper - joint.lower
        return 0 if span <= 0 else round((joint.position - joint.lower) / span * self.SLIDER_STEPS)

    def from_slider(self, name: str, value: int) -> float:
        joint = self.free[name]
        return joint.lower + (joint.upper - joint.lower) * value / self.SLIDER_STEPS
