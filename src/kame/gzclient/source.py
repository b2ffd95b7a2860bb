"""gzclient's ROS side, on the process's one node (kame.client): it follows the scene, the world
statistics, /gazebo/link_states and /gazebo/model_states, keeping the newest of each for the
window to take, and makes the window's requests (pause, step, reset, move, insert, delete) on a thread of
its own, so a slow or absent gzserver never freezes the window. A move dragged faster than the
server answers is sent as its newest pose only."""

from __future__ import annotations

import threading
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from kame.client import services, topics
from kame.client.errors import ROSException
from kame.gzclient import scene_message as sm
from kame.gzclient.model import ModelMove
from kame.gzclient.scene_message import Poses, Vector3

# kame.gazebo's shipped models (its SHIPPED_MODELS), found without importing kame.gazebo: that loads
# MuJoCo, which sets PYOPENGL_PLATFORM=egl for its renderer, and PyOpenGL then finds no context of
# Qt's (GLX) to draw the window in
SHIPPED_MODELS = Path(__file__).resolve().parents[1] / "gazebo" / "models"
SERVICE_TIMEOUT = 5.0  # seconds to wait for a /gazebo service before saying it is not there
SHAPES = {"box": "unit_box", "sphere": "unit_sphere", "cylinder": "unit_cylinder"}  # Gazebo's names for them


@dataclass
class Update:
    """What arrived since the window last took it: the newest of each, or None."""
    scene: sm.SceneMessage | None = None
    stats: sm.WorldStats | None = None
    links: Poses | None = None
    models: Poses | None = None
    problems: list[str] = field(default_factory=list)


def _poses(msg: Any) -> Poses:
    return {name: ((p.position.x, p.position.y, p.position.z),
                   (p.orientation.x, p.orientation.y, p.orientation.z, p.orientation.w))
            for name, p in zip(msg.name, msg.pose, strict=False)}


def shape_sdf(shape: str) -> str:
    return (SHIPPED_MODELS / shape / "model.sdf").read_text()


class ClientSource:
    def __init__(self) -> None:
        from gazebo_msgs.msg import LinkStates, ModelStates
        from std_msgs.msg import String, UInt32

        self._lock = threading.Lock()
        self._update = Update()
        self._pending_move: ModelMove | None = None
        self._calls = ThreadPoolExecutor(max_workers=1, thread_name_prefix="gzclient-calls")
        self._step = topics.Publisher(sm.STEP_TOPIC, UInt32, queue_size=10)
        self._subscribers = [
            topics.Subscriber(sm.SCENE_TOPIC, String, self._on_scene, queue_size=1),
            topics.Subscriber(sm.STATS_TOPIC, String, self._on_stats, queue_size=1),
            topics.Subscriber("/gazebo/link_states", LinkStates, self._on_links, queue_size=1),
            topics.Subscriber("/gazebo/model_states", ModelStates, self._on_models, queue_size=1),
        ]

    # -------------------------------------------------------------- in

    def _problem(self, text: str) -> None:
        with self._lock:
            self._update.problems.append(text)

    def _on_scene(self, msg: Any) -> None:
        try:
            scene = sm.decode_scene(msg.data)
        except sm.SceneMessageError as exc:
            self._problem(f"{sm.SCENE_TOPIC}: {exc}")
            return
        with self._lock:
            self._update.scene = scene

    def _on_stats(self, msg: Any) -> None:
        try:
            stats = sm.decode_stats(msg.data)
        except sm.SceneMessageError as exc:
            self._problem(f"{sm.STATS_TOPIC}: {exc}")
            return
        with self._lock:
            self._update.stats = stats
            if stats.links is not None:  # a paused world's poses (no link_states while paused)
                self._update.links = stats.links
            if stats.models is not None:
                self._update.models = stats.models

    def _on_links(self, msg: Any) -> None:
        poses = _poses(msg)
        with self._lock:
            self._update.links = poses

    def _on_models(self, msg: Any) -> None:
        poses = _poses(msg)
        with self._lock:
            self._update.models = poses

    def take(self) -> Update:
        with self._lock:
            update, self._update = self._update, Update()
        return update

    # -------------------------------------------------------------- out

    def _call(self, name: str, service_class: type[Any], request: Any = None) -> None:
        """Calls /gazebo/`name` on the calls thread; a failure becomes a problem the window shows."""
        def call() -> None:
            proxy = services.ServiceProxy(f"/gazebo/{name}", service_class)
            try:
                proxy.wait_for_service(SERVICE_TIMEOUT)
                answer = proxy() if request is None else proxy(request)
            except (ROSException, OSError) as exc:
                self._problem(f"/gazebo/{name}: {exc}")
                return
            if getattr(answer, "success", True) is False:
                self._problem(f"/gazebo/{name}: {answer.status_message}")

        self._calls.submit(call)

    def set_paused(self, paused: bool) -> None:
        from std_srvs.srv import Empty

        self._call("pause_physics" if paused else "unpause_physics", Empty)

    def step(self, iterations: int = 1) -> None:
        from std_msgs.msg import UInt32

        self._step.publish(UInt32(iterations))

    def reset_world(self) -> None:
        """Gazebo's Edit > Reset Model Poses."""
        from std_srvs.srv import Empty

        self._call("reset_world", Empty)

    def reset_simulation(self) -> None:
        """Gazebo's Edit > Reset World: poses and time."""
        from std_srvs.srv import Empty

        self._call("reset_simulation", Empty)

    def move(self, move: ModelMove) -> None:
        with self._lock:
            queued = self._pending_move is not None
            self._pending_move = move
        if not queued:
            self._calls.submit(self._send_move)

    def _send_move(self) -> None:
        from gazebo_msgs.msg import ModelState
        from gazebo_msgs.srv import SetModelState

        with self._lock:
            move, self._pending_move = self._pending_move, None
        if move is None:
            return
        state = ModelState()
        state.model_name = move.model
        state.pose.position.x, state.pose.position.y, state.pose.position.z = move.position
        o = state.pose.orientation
        o.x, o.y, o.z, o.w = move.orientation
        state.reference_frame = "world"
        try:
            answer = services.ServiceProxy("/gazebo/set_model_state", SetModelState)(state)
        except (ROSException, OSError) as exc:
            self._problem(f"/gazebo/set_model_state: {exc}")
            return
        if not answer.success:
            self._problem(f"/gazebo/set_model_state: {answer.status_message}")

    def insert(self, shape: str, name: str, position: Vector3) -> None:
        """spawn_sdf_model of the shipped simple shape `shape` as `name`, standing at `position`."""
        from gazebo_msgs.srv import SpawnModel, SpawnModelRequest

        request = SpawnModelRequest()
        request.model_name = name
        request.model_xml = shape_sdf(shape)
        request.initial_pose.position.x, request.initial_pose.position.y, request.initial_pose.position.z = position
        request.initial_pose.orientation.w = 1.0
        request.reference_frame = "world"
        self._call("spawn_sdf_model", SpawnModel, request)

    def delete(self, model: str) -> None:
        """Gazebo's Edit > Delete on the selected model."""
        from gazebo_msgs.srv import DeleteModel, DeleteModelRequest

        self._call("delete_model", DeleteModel, DeleteModelRequest(model))

    def close(self) -> None:
        self._calls.shutdown(wait=True, cancel_futures=True)
        for subscriber in self._subscribers:
            subscriber.unregister()
        self._step.unregister()
