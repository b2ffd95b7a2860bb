"""The camera plugins: camera (sensor_msgs/Image and CameraInfo) and the depth cameras
(depth_camera and openni_kinect: the colour image, a 32FC1 depth image in metres, their
CameraInfos, and a PointCloud2 of x y z rgb in the camera's optical frame), on the frames
kame.gazebo renders with MuJoCo.

Topics under <robotNamespace>/<cameraName>/, as gazebo_ros_camera_utils makes its NodeHandle.
CameraInfo: the pinhole K of the rendered image (kame.gazebo.camera: the principal point at the
centre of the image), <focalLength>, <Cx>, <Cy> and <CxPrime> when given; D from <distortionK1..T2>
(plumb_bob: the image itself is not distorted, as Gazebo's camera plugin does not distort it);
P with <hackBaseline>. Depths outside [<pointCloudCutoff>, <pointCloudCutoffMax>] are NaN, as
openni_kinect leaves them.
"""

from __future__ import annotations

import functools
from typing import Any

import numpy as np

from kame.gazebo_ros.conversions import stamp
from kame.gazebo_ros.plugins.base import Every, GazeboPlugin, PluginContext
from kame.gazebo_ros.plugins.parameters import PluginParameterError

CAMERA_MISSING = "Camera plugin missing <{tag}>, defaults to {default}"
ENCODINGS = {"R8G8B8": "rgb8", "RGB_INT8": "rgb8", "B8G8R8": "bgr8", "BGR_INT8": "bgr8", "L8": "mono8",
             "L_INT8": "mono8"}


def depth_in_range(depth: np.ndarray, near: float, far: float) -> np.ndarray:
    """Depths (float32 metres) outside (near, far) or not finite as NaN, as openni_kinect leaves them."""
    depth = np.asarray(depth, dtype=np.float32)
    kept = (depth > near) & (depth < far) & np.isfinite(depth)
    cut: np.ndarray = np.where(kept, depth, np.float32(np.nan))
    return cut


@functools.lru_cache(maxsize=4)
def _optical_rays(height: int, width: int, f: float, cx: float, cy: float) -> tuple[np.ndarray, np.ndarray]:
    """Each pixel's (x / z, y / z) in the optical frame: made once per camera, not per frame."""
    rows, columns = np.indices((height, width), dtype=np.float32)
    return (columns - np.float32(cx)) / np.float32(f), (rows - np.float32(cy)) / np.float32(f)


def point_cloud_bytes(depth: np.ndarray, rgb: np.ndarray, f: float, cx: float, cy: float) -> bytes:
    """PointCloud2 data of x y z rgb (float32 each, rgb packed as openni_kinect packs it) in the
    optical frame, one point a pixel, row by row."""
    height, width = depth.shape
    across, down = _optical_rays(height, width, f, cx, cy)
    points = np.empty((height, width, 4), dtype=np.float32)
    np.multiply(across, depth, out=points[:, :, 0])
    np.multiply(down, depth, out=points[:, :, 1])
    points[:, :, 2] = depth
    colour = points[:, :, 3].view(np.uint32)
    colour[:] = rgb[:, :, 0]
    colour <<= 8
    colour |= rgb[:, :, 1]
    colour <<= 8
    colour |= rgb[:, :, 2]
    return points.tobytes()


class Camera(GazeboPlugin):
    """libgazebo_ros_camera.so."""

    depth = False

    def __init__(self, context: PluginContext) -> None:
        from sensor_msgs.msg import CameraInfo, Image

        super().__init__(context)
        sensor = context.sensor()
        wanted = ("depth", "camera") if self.depth else ("camera", "depth")
        if sensor is None or sensor.type not in wanted:
            raise PluginParameterError(f"{type(self).__name__} plugin must sit in a camera sensor "
                                       f"(<sensor type=\"{wanted[0]}\">)")
        self.sensor = sensor
        self.sensor_info = context.sensor_info()
        p = context.parameters("Camera", CAMERA_MISSING)
        namespace = context.namespace(p)
        camera_name = p.text("cameraName", "", quiet=True).strip("/")
        base = f"{namespace}/{camera_name}".strip("/")
        self.frame = p.text("frameName", "/world").lstrip("/")
        rate = p.number("updateRate", 0.0, quiet=True)
        self.rate = Every(rate if rate > 0 else sensor.update_rate)
        image_topic = p.text("imageTopicName", "image_raw")
        info_topic = p.text("cameraInfoTopicName", "camera_info")
        self.focal_length = p.number("focalLength", 0.0, quiet=True)
        self.cx_prime = p.number("CxPrime", 0.0, quiet=True)
        self.cx = p.number("Cx", 0.0, quiet=True)
        self.cy = p.number("Cy", 0.0, quiet=True)
        self.baseline = p.number("hackBaseline", 0.0, quiet=True)
        self.distortion = [p.number(tag, 0.0, quiet=True) for tag in
                           ("distortionK1", "distortionK2", "distortionT1", "distortionT2", "distortionK3")]
        self.image = self.own(context.publisher(base, image_topic, Image))
        self.info = self.own(context.publisher(base, info_topic, CameraInfo))
        self._start_depth(p, base)
        context.report(p)

    def _start_depth(self, p: Any, base: str) -> None:
        """A colour camera has no depth outputs."""

    def _camera_info(self, config: Any, now: float) -> Any:
        from sensor_msgs.msg import CameraInfo

        k = list(config.k())
        f = self.focal_length or k[0]
        cx = self.cx or k[2]
        cy = self.cy or k[5]
        info = CameraInfo()
        info.header.stamp = stamp(now)
        info.header.frame_id = self.frame
        info.width, info.height = config.width, config.height
        info.distortion_model = "plumb_bob"
        info.D = self.distortion
        info.K = [f, 0.0, cx, 0.0, f, cy, 0.0, 0.0, 1.0]
        info.R = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]
        info.P = [f, 0.0, self.cx_prime or cx, -f * self.baseline, 0.0, f, cy, 0.0, 0.0, 0.0, 1.0, 0.0]
        return info

    def _image(self, pixels: np.ndarray, encoding: str, now: float) -> Any:
        from sensor_msgs.msg import Image

        msg = Image()
        msg.header.stamp = stamp(now)
        msg.header.frame_id = self.frame
        msg.height, msg.width = pixels.shape[0], pixels.shape[1]
        msg.encoding = encoding
        msg.is_bigendian = 0
        msg.step = pixels.strides[0]
        msg.data = pixels.tobytes()
        return msg

    def _wanted(self) -> bool:
        return self.sensor.always_on or self.image.get_num_connections() > 0 or self.info.get_num_connections() > 0

    def update(self, now: float) -> None:
        if not self.rate.due(now) or not self._wanted():
            return
        frame = self.context.world.camera_frame(self.sensor_info, rgb=True, depth=self.depth)
        config = frame.config
        encoding = ENCODINGS.get(config.format, "rgb8")
        pixels = frame.rgb
        if encoding == "bgr8":
            pixels = np.ascontiguousarray(pixels[:, :, ::-1])
        elif encoding == "mono8":
            pixels = np.ascontiguousarray(pixels.mean(axis=2).astype(np.uint8))
        self.image.publish(self._image(pixels, encoding, now))
        self.info.publish(self._camera_info(config, now))
        if self.depth:
            self._publish_depth(frame, now)

    def _publish_depth(self, frame: Any, now: float) -> None:
        """A colour camera publishes no depth."""


class DepthCamera(Camera):
    """libgazebo_ros_depth_camera.so and libgazebo_ros_openni_kinect.so."""

    depth = True

    def _start_depth(self, p: Any, base: str) -> None:
        from sensor_msgs.msg import CameraInfo, Image, PointCloud2

        self.cutoff = p.number("pointCloudCutoff", 0.4, quiet=True)
        self.cutoff_max = p.number("pointCloudCutoffMax", 5.0, quiet=True)
        self.depth_image = self.own(self.context.publisher(
            base, p.text("depthImageTopicName", "depth/image_raw", quiet=True), Image))
        self.depth_info = self.own(self.context.publisher(
            base, p.text("depthImageCameraInfoTopicName", "depth/camera_info", quiet=True), CameraInfo))
        self.points = self.own(self.context.publisher(
            base, p.text("pointCloudTopicName", "points", quiet=True), PointCloud2))

    def _wanted(self) -> bool:
        return super()._wanted() or any(t.get_num_connections() > 0
                                        for t in (self.depth_image, self.depth_info, self.points))

    def _publish_depth(self, frame: Any, now: float) -> None:
        from sensor_msgs.msg import PointCloud2, PointField

        config = frame.config
        depth = depth_in_range(frame.depth, self.cutoff, self.cutoff_max)
        self.depth_image.publish(self._image(depth, "32FC1", now))
        info = self._camera_info(config, now)
        self.depth_info.publish(info)
        if self.points.get_num_connections() == 0:
            return
        msg = PointCloud2()
        msg.header.stamp = stamp(now)
        msg.header.frame_id = self.frame
        msg.height, msg.width = depth.shape
        msg.fields = [PointField("x", 0, PointField.FLOAT32, 1), PointField("y", 4, PointField.FLOAT32, 1),
                      PointField("z", 8, PointField.FLOAT32, 1), PointField("rgb", 12, PointField.FLOAT32, 1)]
        msg.is_bigendian = False
        msg.point_step = 16
        msg.row_step = 16 * depth.shape[1]
        msg.data = point_cloud_bytes(depth, frame.rgb, info.K[0], info.K[2], info.K[5])
        msg.is_dense = False
        self.points.publish(msg)
