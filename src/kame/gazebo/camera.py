"""Camera and depth sensors rendered offscreen by MuJoCo (EGL, headless): RGB images, depth
images in metres along the optical axis (as Gazebo's depth cameras give them), and the pinhole
K matrix a CameraInfo carries.

Cameras draw visuals only (collision shapes are MuJoCo geoms in another group), on the world's
<scene> background (where the depth buffer shows nothing drawn: a sky box would have depth). One
GL context per image size, remade when the world's model is rebuilt; `close()` frees them. Each frame is one
render whose colour and depth buffers are both read (mujoco.Renderer renders twice for the two),
without multisampling: on Mesa's software renderer 4x multisampling made a 640x480 frame 8 times
slower (bench/gazebo_bench.py). A camera's near and far clip and field of view are set on the
model just before it renders, since MuJoCo keeps one clip range for the whole model.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from kame.gazebo.assembly import VISUAL_GROUP
from kame.gazebo.engine import BACKEND, gl_context_class, mujoco
from kame.gazebo.errors import GazeboError
from kame.gazebo.xmltree import Element

EGL_PACKAGES = ("libegl1", "libopengl0", "libegl-mesa0", "libgl1-mesa-dri")  # scripts/install-gui-libs.sh --xvfb


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
        width = image.integer("width", 320) if image is not None else 320
        height = image.integer("height", 240) if image is not None else 240
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


def optical_points(depth: np.ndarray, config: CameraConfig) -> np.ndarray:
    """Each pixel's point (height x width x 3, float32) in the camera's optical frame (x right, y
    down, z forward), as a depth camera's PointCloud2 carries them; NaN where the depth is +inf."""
    fx, _, cx, _, fy, cy, *_ = config.k()
    rows, cols = np.indices(depth.shape, dtype=np.float32)
    z = np.where(np.isfinite(depth), depth, np.nan).astype(np.float32)
    return np.stack(((cols - cx) * z / fx, (rows - cy) * z / fy, z), axis=-1)


@dataclass(frozen=True)
class CameraFrame:
    rgb: np.ndarray | None  # height x width x 3, uint8, top row first
    depth: np.ndarray | None  # height x width, float32 metres; +inf where nothing is within the far clip
    config: CameraConfig


class _Offscreen:
    """One GL context with MuJoCo's offscreen buffer, a scene and the frame's buffers, of one size."""

    def __init__(self, model: mujoco.MjModel, width: int, height: int) -> None:
        self.context = gl_context_class()(width, height)
        self.context.make_current()
        self.renderer = mujoco.MjrContext(model, mujoco.mjtFontScale.mjFONTSCALE_150.value)
        mujoco.mjr_setBuffer(mujoco.mjtFramebuffer.mjFB_OFFSCREEN.value, self.renderer)
        self.renderer.readDepthMap = mujoco.mjtDepthMap.mjDEPTH_ZEROFAR
        self.scene = mujoco.MjvScene(model, maxgeom=10000)
        self.rect = mujoco.MjrRect(0, 0, width, height)
        self.rgb = np.empty((height, width, 3), dtype=np.uint8)
        self.depth = np.empty((height, width), dtype=np.float32)

    def free(self) -> None:
        self.context.make_current()
        self.renderer.free()
        self.context.free()


class Cameras:
    """The GL renderers of one world's cameras."""

    def __init__(self) -> None:
        self._offscreen: dict[tuple[int, int], _Offscreen] = {}
        self._generation = -1
        self._option = mujoco.MjvOption()
        self._option.geomgroup[:] = 0
        self._option.geomgroup[VISUAL_GROUP] = 1
        self._option.sitegroup[:] = 0
        self._camera = mujoco.MjvCamera()
        self._camera.type = mujoco.mjtCamera.mjCAMERA_FIXED

    def render(self, model: mujoco.MjModel, data: mujoco.MjData, generation: int, camera: str, config: CameraConfig,
               rgb: bool, depth: bool, rng: np.random.Generator, background: tuple[float, ...]) -> CameraFrame:
        camera_id = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_CAMERA, camera)
        if camera_id < 0:
            raise GazeboError(f"no camera sensor named {camera!r}")
        if generation != self._generation:
            self.close()
            self._generation = generation
        size = (config.width, config.height)
        if size not in self._offscreen:
            try:
                self._offscreen[size] = _Offscreen(model, *size)
            except Exception as exc:  # no GL: PyOpenGL's, EGL's and MuJoCo's errors differ by what is missing
                raise GazeboError(f"MuJoCo cannot render camera {camera!r} with MUJOCO_GL="
                                  f"{BACKEND}: {exc} (headless rendering needs EGL: "
                                  f"apt-get install {' '.join(EGL_PACKAGES)})") from None
        offscreen = self._offscreen[size]
        model.cam_fovy[camera_id] = math.degrees(config.vertical_fov())
        model.vis.map.znear = config.near / model.stat.extent
        model.vis.map.zfar = config.far / model.stat.extent
        self._camera.fixedcamid = camera_id
        offscreen.context.make_current()
        mujoco.mjv_updateScene(model, data, self._option, None, self._camera, mujoco.mjtCatBit.mjCAT_ALL.value,
                               offscreen.scene)
        mujoco.mjr_render(offscreen.rect, offscreen.scene, offscreen.renderer)
        mujoco.mjr_readPixels(offscreen.rgb if rgb else None, offscreen.depth, offscreen.rect, offscreen.renderer)
        image = np.flipud(offscreen.rgb).copy() if rgb else None  # GL's rows run bottom up
        if image is not None:  # where nothing was drawn (the depth buffer still at the far clip): the background
            image[np.flipud(offscreen.depth) <= 0.0] = np.round(np.asarray(background[:3]) * 255).astype(np.uint8)
        if image is not None and config.noise_stddev > 0:
            noisy = image + rng.normal(config.noise_mean * 255, config.noise_stddev * 255, image.shape)
            image = np.clip(noisy, 0, 255).astype(np.uint8)
        distances = _metres(np.flipud(offscreen.depth), config.near, config.far) if depth else None
        return CameraFrame(image, distances, config)

    def close(self) -> None:
        for offscreen in self._offscreen.values():
            offscreen.free()
        self._offscreen.clear()


def _metres(buffer: np.ndarray, near: float, far: float) -> np.ndarray:
    """MuJoCo's reversed-Z depth buffer (1 at the near clip, 0 at the far one) as distances along the
    optical axis, +inf at the far clip; the same projection as mujoco.Renderer undoes, in float32 as
    glFrustum builds it and float64 to invert it."""
    znear, zfar = np.float32(near), np.float32(far)
    c_coef = np.float32(-0.5) * (-(zfar + znear) / (zfar - znear)) - np.float32(0.5)
    d_coef = np.float32(-0.5) * (-(np.float32(2) * zfar * znear) / (zfar - znear))
    distances = (float(d_coef) / (buffer.astype(np.float64) + float(c_coef))).astype(np.float32)
    distances[distances >= far * 0.999] = np.inf
    return distances
