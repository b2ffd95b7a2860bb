"""What a world is made of, as SDF and URDF describe it, before MuJoCo sees it: plain values.

Poses here are final: a link's pose is in its model's frame, a visual's, collision's and
sensor's in its link's frame, a joint's in its child link's frame, a model's in the world. A
nested model is flattened into its parent, its links and joints named "inner::link".
"""

from __future__ import annotations

from dataclasses import dataclass, field

from kame.gazebo.poses import IDENTITY, Pose, Vector3
from kame.gazebo.xmltree import Element

Color = tuple[float, float, float, float]
GRAY: Color = (0.7, 0.7, 0.7, 1.0)


@dataclass(frozen=True)
class Geometry:
    kind: str  # box, cylinder, sphere, plane, mesh
    size: tuple[float, ...] = ()  # box: x y z; cylinder: radius length; sphere: radius; plane: x y
    normal: Vector3 = (0.0, 0.0, 1.0)  # plane only
    mesh_uri: str = ""  # mesh only: the uri as written
    mesh_file: str = ""  # mesh only: the file it names
    scale: Vector3 = (1.0, 1.0, 1.0)


@dataclass(frozen=True)
class Visual:
    name: str
    geometry: Geometry
    pose: Pose
    color: Color = GRAY


@dataclass(frozen=True)
class Collision:
    name: str
    geometry: Geometry
    pose: Pose
    mu: float = 1.0  # ODE's default friction coefficients
    mu2: float = 1.0
    gazebo_name: str = ""  # "link::collision" as Gazebo names it (a URDF's fixed-joint lumping renames both)


@dataclass(frozen=True)
class Inertial:
    mass: float = 1.0  # SDF's defaults: 1 kg, unit diagonal inertia
    pose: Pose = IDENTITY
    ixx: float = 1.0
    iyy: float = 1.0
    izz: float = 1.0
    ixy: float = 0.0
    ixz: float = 0.0
    iyz: float = 0.0


@dataclass(frozen=True)
class Sensor:
    name: str
    type: str  # ray, gpu_ray, sonar, camera, depth, imu, contact, ...
    pose: Pose  # in its link's frame
    update_rate: float
    always_on: bool
    visualize: bool
    element: Element  # the <sensor> element: its configuration as the sensor (and its plugins) read it


@dataclass(frozen=True)
class Plugin:
    name: str
    filename: str
    model: str  # "" for a world plugin
    link: str  # the link whose sensor carries it, or ""
    sensor: str  # the sensor it sits in, or ""
    element: Element  # the <plugin> element: its children are the plugin's parameters

    def parameters(self) -> dict[str, str]:
        """Each child element's text, by tag (the last one when repeated)."""
        return {c.tag: c.text.strip() for c in self.element.children}


@dataclass(frozen=True)
class Link:
    name: str
    pose: Pose  # in the model's frame
    inertial: Inertial = Inertial()
    visuals: tuple[Visual, ...] = ()
    collisions: tuple[Collision, ...] = ()
    sensors: tuple[Sensor, ...] = ()
    gravity: bool = True
    kinematic: bool = False
    self_collide: bool = False  # Gazebo's default: a model's links do not collide with each other


@dataclass(frozen=True)
class JointAxis:
    xyz: Vector3  # in the child link's frame
    lower: float = -1e16  # SDF's "no limit"
    upper: float = 1e16
    effort: float = -1.0  # below 0: no limit
    velocity: float = -1.0
    damping: float = 0.0
    friction: float = 0.0
    spring_stiffness: float = 0.0  # SDF 1.5's <dynamics>: a spring pulling toward spring_reference
    spring_reference: float = 0.0

    def limited(self) -> bool:
        return self.lower > -1e15 and self.upper < 1e15 and self.lower < self.upper


@dataclass(frozen=True)
class Joint:
    name: str
    type: str  # revolute, continuous, prismatic, fixed, ball
    parent: str  # a link of the model, or "world"
    child: str
    pose: Pose  # in the child link's frame
    axis: JointAxis = JointAxis((0.0, 0.0, 1.0))


@dataclass(frozen=True)
class Model:
    name: str
    pose: Pose  # in the world
    static: bool = False
    links: tuple[Link, ...] = ()
    joints: tuple[Joint, ...] = ()
    plugins: tuple[Plugin, ...] = ()
    source: str = ""  # the file (or "<string>") it came from, for messages

    def link(self, name: str) -> Link | None:
        return next((link for link in self.links if link.name == name), None)


@dataclass(frozen=True)
class Light:
    name: str
    type: str  # directional, point, spot
    pose: Pose
    diffuse: Color = (1.0, 1.0, 1.0, 1.0)
    specular: Color = (0.1, 0.1, 0.1, 1.0)
    direction: Vector3 = (0.0, 0.0, -1.0)
    cast_shadows: bool = False
    attenuation_range: float = 10.0


@dataclass(frozen=True)
class Physics:
    max_step_size: float = 0.001
    real_time_update_rate: float = 1000.0
    real_time_factor: float = 1.0
    gravity: Vector3 = (0.0, 0.0, -9.8)


@dataclass(frozen=True)
class Scene:
    """A world's <scene>: what cameras see behind everything, and the light from everywhere."""

    ambient: Color = (0.4, 0.4, 0.4, 1.0)  # Gazebo's defaults
    background: Color = (0.7, 0.7, 0.7, 1.0)


@dataclass(frozen=True)
class World:
    name: str = "default"
    physics: Physics = Physics()
    scene: Scene = Scene()
    models: tuple[Model, ...] = ()
    lights: tuple[Light, ...] = ()
    plugins: tuple[Plugin, ...] = field(default=())
    source: str = "<string>"
