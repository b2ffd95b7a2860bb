"""Camera and depth sensors rendered offscreen by MuJoCo (EGL, headless): RGB images, depth
images in metres along the optical axis (as Gazebo's depth cameras give them), and the pinhole
K matrix a CameraInfo carries.

Cameras draw visuals only (collision shapes are MuJoCo geoms in another group). One MuJoCo
Renderer (one GL context) per image size, remade when the world's model is rebuilt; `close()`
frees them. A camera's near and far clip and field of view are set on the model just before it
renders, since MuJoCo keeps one clip range for the whole model.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from kame.gazebo.assembly import VISUAL_GROUP
from kame.gazebo.engine import mujoco
from kame.gazebo.errors import GazeboError
from kame.gazebo.xmltree import Element


@dataclass(frozen=True)
class CameraConfig:
    width: int = 320  # SDF's defaults
    height: int = 240
    horizontal_fov: float = 1.047
    near: float = 0.1
    far: float = 100.0
    format: str = "R8G8B8"
    noise_mean: float = 0.0
    noise_stddev: float = 0.0

    @staticmethod
    def of(sensor: Element) -> CameraConfig:
        camera = sensor.child("camera")
        if camera is None:
            return CameraConfig()
        image, clip = camera.child("image"), camera.child("clip")
        width = int(image.number("width", 320)) if image is not None else 320
        height = int(image.number("height", 240)) if image is not None else 240
        config = CameraConfig(width, height, camera.number("horizontal_fov", 1.047),
                              clip.number("near", 0.1) if clip is not None else 0.1,
                              clip.number("far", 100.0) if clip is not None else 100.0,
                              (image.child_text("format") or "R8G8B8") if image is not None else "R8G8B8",
                              *_noise(camera.child("noise")))
        if not (0 < width <= 8192 and 0 < height <= 8192):
            raise GazeboError(f"{camera.where()}: an image of {width}x{height} pixels cannot be rendered")
        if not (0 < config.horizontal_fov < math.pi) or not (0 < config.near < config.far):
            raise GazeboError(f"{camera.where()}: needs 0 < horizontal_fov < pi and 0 < near < far")
        return config

    def focal_length(self) -> float:
        return self.width / (2.0 * math.tan(self.horizontal_fov / 2.0))

    def k(self) -> tuple[float, ...]:
        """The 3x3 intrinsic matrix, row-major: square pixels, the principal point at the image's
        centre ((w - 1) / 2 in pixel-centre coordinates, where the renderer puts it)."""
        f = self.focal_length()
        return (f, 0.0, (self.width - 1) / 2.0, 0.0, f, (self.height - 1) / 2.0, 0.0, 0.0, 1.0)

    def vertical_fov(self) -> float:
        return 2.0 * math.atan(math.tan(self.horizontal_fov / 2.0) * self.height / self.width)


def _noise(noise: Element | None) -> tuple[float, float]:
    if noise is None or (noise.child_text("type") or "gaussian") != "gaussian":
        return 0.0, 0.0
    return noise.number("mean", 0.0), noise.number("stddev", 0.0)


@dataclass(frozen=True)
class CameraFrame:
    rgb: np.ndarray | None  # height x width x 3, uint8, top row first
    depth: np.ndarray | None  # height x width, float32 metres; +inf where nothing is within the far clip
    config: CameraConfig


class Cameras:
    """The GL renderers of one world's cameras."""

    def __init__(self) -> None:
        self._renderers: dict[tuple[int, int], mujoco.Renderer] = {}
        self._generation = -1
        self._option = mujoco.MjvOption()
        self._option.geomgroup[:] = 0
        self._option.geomgroup[VISUAL_GROUP] = 1
        self._option.sitegroup[:] = 0

    def render(self, model: mujoco.MjModel, data: mujoco.MjData, generation: int, camera: str, config: CameraConfig,
               rgb: bool, depth: bool, rng: np.random.Generator) -> CameraFrame:
        camera_id = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_CAMERA, camera)
        if camera_id < 0:
            raise GazeboError(f"no camera sensor named {camera!r}")
        if generation != self._generation:
            self.close()
            self._generation = generation
        size = (config.width, config.height)
        if size not in self._renderers:
            self._renderers[size] = mujoco.Renderer(model, config.height, config.width)
        renderer = self._renderers[size]
        model.cam_fovy[camera_id] = math.degrees(config.vertical_fov())
        model.vis.map.znear = config.near / model.stat.extent
        model.vis.map.zfar = config.far / model.stat.extent
        renderer.update_scene(data, camera_id, self._option)
        image = renderer.render().copy() if rgb else None
        if image is not None and config.noise_stddev > 0:
            noisy = image + rng.normal(config.noise_mean * 255, config.noise_stddev * 255, image.shape)
            image = np.clip(noisy, 0, 255).astype(np.uint8)
        distances = None
        if depth:
            renderer.enable_depth_rendering()
            try:
                distances = renderer.render().astype(np.float32)
            finally:
                renderer.disable_depth_rendering()
            distances[distances >= config.far * 0.999] = np.inf
        return CameraFrame(image, distances, config)

    def close(self) -> None:
        for renderer in self._renderers.values():
            renderer.close()
        self._renderers.clear()
