"""move_base's parameters as turtlebot_navigation's YAML files lay them out, pure: read through a
`get(name, default)` over the node's private namespace, with move_base's and costmap_2d's
defaults.

    ~controller_frequency, ~planner_frequency, ~controller_patience, ~planner_patience,
    ~conservative_reset_dist, ~clearing_rotation_allowed, ~recovery_behavior_enabled,
    ~recovery_behaviors, ~base_local_planner, ~base_global_planner     (move_base_params.yaml)
    ~global_costmap/..., ~local_costmap/...: global_frame, robot_base_frame, update_frequency,
    publish_frequency, rolling_window, width, height, resolution, footprint or robot_radius,
    inflation_layer/{inflation_radius, cost_scaling_factor}, obstacle_layer/{obstacle_range,
    raytrace_range, track_unknown_space, observation_sources, <source>/{topic, data_type,
    marking, clearing, obstacle_range, raytrace_range}}                 (costmap_*_params.yaml)
    ~DWAPlannerROS/... or ~TrajectoryPlannerROS/...                    (dwa_local_planner_params.yaml)

A layer parameter is also taken from the costmap's own namespace (costmap_2d's pre-Hydro
layout: ~global_costmap/inflation_radius), as costmap_2d does when it converts old parameters.
"""

from __future__ import annotations

import ast
import math
from collections.abc import Callable
from dataclasses import dataclass, field, fields
from typing import Any

from kame.nav.costmap import CostmapParams
from kame.nav.local_planner import LocalPlannerParams

Getter = Callable[[str, Any], Any]


class ConfigError(ValueError):
    """A parameter move_base cannot work with (said as move_base would, then the node stops)."""


@dataclass(frozen=True)
class Source:
    """One of the obstacle layer's observation_sources."""

    name: str
    topic: str
    data_type: str = "LaserScan"
    marking: bool = True
    clearing: bool = True


@dataclass(frozen=True)
class CostmapConfig:
    name: str  # global_costmap or local_costmap
    global_frame: str
    robot_base_frame: str
    update_frequency: float
    publish_frequency: float
    rolling_window: bool
    width: float  # metres (rolling window only; a static map sets its own size)
    height: float
    resolution: float
    footprint: tuple[tuple[float, float], ...]  # empty: a round robot of robot_radius
    robot_radius: float
    layers: CostmapParams
    sources: tuple[Source, ...]
    static_map: bool = True

    @property
    def inscribed_radius(self) -> float:
        return inscribed_radius(self.footprint) if self.footprint else self.robot_radius

    @property
    def circumscribed_radius(self) -> float:
        return max(math.hypot(x, y) for x, y in self.footprint) if self.footprint else self.robot_radius


@dataclass(frozen=True)
class Recovery:
    name: str
    kind: str  # clear_costmap_recovery/ClearCostmapRecovery, rotate_recovery/RotateRecovery
    reset_distance: float = 3.0  # ClearCostmapRecovery: obstacles farther than this are cleared


@dataclass(frozen=True)
class MoveBaseConfig:
    controller_frequency: float = 20.0
    planner_frequency: float = 0.0
    controller_patience: float = 15.0
    planner_patience: float = 5.0
    max_planning_retries: int = -1
    oscillation_timeout: float = 0.0
    oscillation_distance: float = 0.5
    conservative_reset_dist: float = 3.0
    clearing_rotation_allowed: bool = True
    recovery_behavior_enabled: bool = True
    base_local_planner: str = "base_local_planner/TrajectoryPlannerROS"
    base_global_planner: str = "navfn/NavfnROS"
    recoveries: tuple[Recovery, ...] = field(default_factory=tuple)

    @property
    def local_planner_name(self) -> str:
        """The local planner's namespace and topic prefix: DWAPlannerROS or TrajectoryPlannerROS."""
        return self.base_local_planner.rsplit("/", 1)[-1]

    @property
    def global_planner_name(self) -> str:
        return self.base_global_planner.rsplit("/", 1)[-1]


CLEAR = "clear_costmap_recovery/ClearCostmapRecovery"
ROTATE = "rotate_recovery/RotateRecovery"
KNOWN_RECOVERIES = (CLEAR, ROTATE)


def parse_footprint(value: Any) -> tuple[tuple[float, float], ...]:
    """costmap_2d's footprint: a list of [x, y] points or the same as a string; [] means none."""
    if isinstance(value, str):
        try:
            value = ast.literal_eval(value.strip() or "[]")
        except (ValueError, SyntaxError):
            raise ConfigError(f"The footprint must be specified as list of lists on the parameter server, "
                              f"but it was {value!r}") from None
    if not isinstance(value, list | tuple):
        raise ConfigError(f"The footprint must be a list of [x, y] points, not {value!r}")
    points = []
    for point in value:
        if not isinstance(point, list | tuple) or len(point) != 2 \
                or not all(isinstance(v, int | float) and math.isfinite(v) for v in point):
            raise ConfigError(f"The footprint must be a list of [x, y] points; {point!r} is not one")
        points.append((float(point[0]), float(point[1])))
    if points and len(points) < 3:
        raise ConfigError("You must specify at least three points for the robot footprint")
    return tuple(points)


def inscribed_radius(footprint: tuple[tuple[float, float], ...]) -> float:
    """The distance from the robot's centre to the footprint's nearest edge (costmap_2d's
    calculateMinAndMaxDistances)."""
    nearest = math.inf
    for (x0, y0), (x1, y1) in zip(footprint, footprint[1:] + footprint[:1], strict=True):
        dx, dy = x1 - x0, y1 - y0
        length = dx * dx + dy * dy
        t = 0.0 if length == 0 else max(0.0, min(1.0, -(x0 * dx + y0 * dy) / length))
        nearest = min(nearest, math.hypot(x0 + t * dx, y0 + t * dy))
    return nearest


def _number(get: Getter, name: str, default: float) -> float:
    value = get(name, default)
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        raise ConfigError(f"parameter ~{name} must be a finite number, not {value!r}")
    return float(value)


def _layer(get: Getter, ns: str, layer: str, name: str, default: Any) -> Any:
    return get(f"{ns}/{layer}/{name}", get(f"{ns}/{name}", default))


def costmap_config(get: Getter, name: str) -> CostmapConfig:
    rolling = bool(get(f"{name}/rolling_window", False))
    footprint = parse_footprint(get(f"{name}/footprint", []))
    radius = _number(get, f"{name}/robot_radius", 0.46)
    inscribed = inscribed_radius(footprint) if footprint else radius
    obstacle_range = float(_layer(get, name, "obstacle_layer", "obstacle_range", 2.5))
    raytrace_range = float(_layer(get, name, "obstacle_layer", "raytrace_range", 3.0))
    layers = CostmapParams(
        robot_radius=inscribed,
        inflation_radius=float(_layer(get, name, "inflation_layer", "inflation_radius", 0.55)),
        cost_scaling_factor=float(_layer(get, name, "inflation_layer", "cost_scaling_factor", 10.0)),
        lethal_cost_threshold=int(_layer(get, name, "static_layer", "lethal_cost_threshold", 100)),
        track_unknown_space=bool(_layer(get, name, "obstacle_layer", "track_unknown_space", False)) and not rolling,
        obstacle_range=obstacle_range, raytrace_range=raytrace_range)
    names = str(_layer(get, name, "obstacle_layer", "observation_sources", "scan")).split()
    sources = []
    for source in names:
        def option(key: str, default: Any, source: str = source) -> Any:
            return _layer(get, name, "obstacle_layer", f"{source}/{key}", default)
        sources.append(Source(source, str(option("topic", source)), str(option("data_type", "LaserScan")),
                              bool(option("marking", True)), bool(option("clearing", True))))
    # one range pair for all sources: the first laser's own, when it gives them
    scans = [s for s in sources if s.data_type == "LaserScan"]
    if scans:
        first = scans[0].name
        layers = CostmapParams(**{**{f.name: getattr(layers, f.name) for f in fields(CostmapParams)},
                                  "obstacle_range": float(_layer(get, name, "obstacle_layer",
                                                                 f"{first}/obstacle_range", obstacle_range)),
                                  "raytrace_range": float(_layer(get, name, "obstacle_layer",
                                                                 f"{first}/raytrace_range", raytrace_range))})
    resolution = _number(get, f"{name}/resolution", 0.05)
    if resolution <= 0:
        raise ConfigError(f"parameter ~{name}/resolution must be above 0")
    return CostmapConfig(
        name=name,
        global_frame=str(get(f"{name}/global_frame", "map" if name == "global_costmap" else "odom")).lstrip("/"),
        robot_base_frame=str(get(f"{name}/robot_base_frame", "base_link")).lstrip("/"),
        update_frequency=_number(get, f"{name}/update_frequency", 5.0),
        publish_frequency=_number(get, f"{name}/publish_frequency", 0.0),
        rolling_window=rolling, width=_number(get, f"{name}/width", 10.0),
        height=_number(get, f"{name}/height", 10.0), resolution=resolution,
        footprint=footprint, robot_radius=radius, layers=layers, sources=tuple(sources),
        static_map=bool(get(f"{name}/static_map", not rolling)))


def recoveries(get: Getter, conservative_reset_dist: float, circumscribed: float,
               rotation_allowed: bool) -> tuple[Recovery, ...]:
    """~recovery_behaviors as given, else move_base's defaults: conservative_reset, rotate_recovery,
    aggressive_reset, rotate_recovery (the rotations only when clearing_rotation_allowed)."""
    listed = get("recovery_behaviors", None)
    if listed is None:
        found = [Recovery("conservative_reset", CLEAR, conservative_reset_dist)]
        if rotation_allowed:
            found.append(Recovery("rotate_recovery", ROTATE))
        found.append(Recovery("aggressive_reset", CLEAR, circumscribed * 4))
        if rotation_allowed:
            found.append(Recovery("rotate_recovery", ROTATE))
        return tuple(found)
    if not isinstance(listed, list):
        raise ConfigError("The recovery behavior specification must be a list, but is of another type.")
    found = []
    for entry in listed:
        if not isinstance(entry, dict) or "name" not in entry or "type" not in entry:
            raise ConfigError("Recovery behaviors must be specified as maps with a name and a type, "
                              f"not {entry!r}")
        kind = str(entry["type"])
        if kind not in KNOWN_RECOVERIES:
            raise ConfigError(f"Failed to create the {kind} recovery behavior: kame's move_base has "
                              f"{' and '.join(KNOWN_RECOVERIES)}")
        name = str(entry["name"])
        found.append(Recovery(name, kind, _number(get, f"{name}/reset_distance", 3.0)))
    return tuple(found)


def move_base_config(get: Getter, circumscribed: float) -> MoveBaseConfig:
    defaults = MoveBaseConfig()
    values: dict[str, Any] = {}
    for spec in fields(MoveBaseConfig):
        if spec.name == "recoveries":
            continue
        default = getattr(defaults, spec.name)
        if isinstance(default, bool):
            values[spec.name] = bool(get(spec.name, default))
        elif isinstance(default, str):
            values[spec.name] = str(get(spec.name, default))
        elif isinstance(default, int):
            values[spec.name] = int(_number(get, spec.name, default))
        else:
            values[spec.name] = _number(get, spec.name, default)
    if values["controller_frequency"] <= 0:
        raise ConfigError("parameter ~controller_frequency must be above 0")
    values["recoveries"] = recoveries(get, values["conservative_reset_dist"], circumscribed,
                                      values["clearing_rotation_allowed"])
    return MoveBaseConfig(**values)


def local_planner_params(get: Getter, namespace: str, controller_frequency: float) -> LocalPlannerParams:
    """The local planner's parameters from ~<namespace>/ (dwa_local_planner's names; the older
    TrajectoryPlannerROS's max_vel_theta and vtheta_samples are its max_rot_vel and vth_samples)."""
    aliases = {"max_rot_vel": ("max_vel_theta", "max_rot_vel"), "vth_samples": ("vtheta_samples", "vth_samples")}
    values: dict[str, Any] = {}
    defaults = LocalPlannerParams()
    for spec in fields(LocalPlannerParams):
        if spec.name == "controller_frequency":
            values[spec.name] = controller_frequency
            continue
        default = getattr(defaults, spec.name)
        for alias in aliases.get(spec.name, (spec.name,)):
            default = get(f"{namespace}/{alias}", default)
        values[spec.name] = int(default) if isinstance(getattr(defaults, spec.name), int) else float(default)
    return LocalPlannerParams(**values)
