"""cameracalibrator.py on a stereo pair: `rosrun camera_calibration cameracalibrator.py --size 8x6
--square 0.108 right:=/my_stereo/right/image_raw left:=/my_stereo/left/image_raw
right_camera:=/my_stereo/right left_camera:=/my_stereo/left [--approximate 0.01]`.

The left and right images are paired by stamp (within --approximate seconds when given, as
message_filters' ApproximateTimeSynchronizer); the window shows them side by side, rectified once
calibrated with the epipolar error ("epi.") and the board's square size ("dim"). SAVE writes the
views as left-NNNN.png and right-NNNN.png, left.yaml, right.yaml and ost.txt; COMMIT sends each
camera its calibration (left_camera/set_camera_info, right_camera/set_camera_info).
"""

from __future__ import annotations

import threading
from typing import Any

import numpy as np

from kame.camera.calibration_display import render
from kame.camera.calibration_report import camera_info, ost_txt, ost_yaml, report
from kame.camera.cameracalibrator import CalibrationNode, png
from kame.camera.image_feed import subscribe_image
from kame.camera.pictures import PictureError, to_bgr
from kame.camera.stamp_pairs import StampPairs
from kame.camera.stereo_calibrator import StereoCalibrator, epipolar_error, square_size
from kame.client import log


class StereoCalibrationNode(CalibrationNode):
    def __init__(self, cv2: Any, calibrator: StereoCalibrator, cameras: tuple[str, str], slop: float) -> None:
        # the base reads only goodenough and calibration of its calibrator, which a stereo one has too
        super().__init__(cv2, calibrator, cameras[0])  # type: ignore[arg-type]
        self.stereo = calibrator
        self.cameras = cameras
        self.pairs = StampPairs(slop)
        self.pairs_lock = threading.Lock()

    def start(self, topics: list[str], queue_size: int) -> None:
        left_topic, right_topic = topics
        self.subscribers = [subscribe_image(left_topic, "raw", self._left, queue_size=queue_size),
                            subscribe_image(right_topic, "raw", self._right, queue_size=queue_size)]
        self.worker.start()

    def _left(self, image: Any) -> None:
        with self.pairs_lock:
            pair = self.pairs.add_image(image)
        if pair is not None:
            self._arrive(pair)

    def _right(self, image: Any) -> None:
        with self.pairs_lock:
            pair = self.pairs.add_info(image)
        if pair is not None:
            self._arrive(pair)

    def handle_message(self, pair: Any) -> None:
        try:
            left, right = (to_bgr(image, "camera_calibration") for image in pair)
        except PictureError as exc:
            log.emit_throttle(5.0, log.ERROR, "%s", (exc,))
            return
        self.show(self.process_pair(left, right))

    def process_pair(self, left: np.ndarray, right: np.ndarray) -> np.ndarray:
        cv2, board = self.cv2, self.stereo.board
        with self.lock:
            try:
                left_corners, right_corners, kept = self.stereo.handle(left, right)
            except ValueError as exc:
                log.emit_throttle(5.0, log.ERROR, "%s", (exc,))
                return self.last_display if self.last_display is not None else left
            calibration = self.stereo.calibration
            if calibration is not None:
                left, right = self.stereo.rectify(left, right)
            readouts: list[tuple[str, float | None]] = [("epi.", None), ("dim", None)]
            if calibration is not None and left_corners is not None and right_corners is not None:
                left_corners, right_corners = self.stereo.rectified_corners(left_corners, right_corners)
                readouts = [("epi.", epipolar_error(left_corners, right_corners)),
                            ("dim", square_size(cv2, calibration, left_corners, right_corners, board))]
            scribs = []
            for picture, corners in ((left, left_corners), (right, right_corners)):
                scrib = cv2.cvtColor(picture, cv2.COLOR_GRAY2BGR) if picture.ndim == 2 else picture.copy()
                if corners is not None:
                    cv2.drawChessboardCorners(scrib, (board.cols, board.rows), corners.astype(np.float32), True)
                scribs.append(scrib)
            if kept:
                p_x, p_y, p_size, skew = self.stereo.views[-1].params
                print(f"*** Added sample {len(self.stereo.views)}, p_x = {p_x:.3f}, p_y = {p_y:.3f}, "
                      f"p_size = {p_size:.3f}, skew = {skew:.3f}", flush=True)
            side_by_side = np.hstack(scribs)
            self.picture_width = side_by_side.shape[1]
            return render(cv2, side_by_side, self.stereo.progress(), self.stereo.goodenough, calibration is not None,
                          readouts)

    def calibrate(self) -> None:
        print("**** Calibrating ****", flush=True)
        with self.lock:
            calibration = self.stereo.calibrate()
            name = self.stereo.camera_name
            print("stereo pinhole calibration...")
            for side, part in (("Left", calibration.left), ("Right", calibration.right)):
                print(f"\n{side}:\n{report(part)}")
            print("\nself.T =", np.ravel(calibration.translation).tolist())
            print("self.R =", np.ravel(calibration.rotation).tolist())
            print(ost_txt(calibration.left, name + "/left") + ost_txt(calibration.right, name + "/right"), flush=True)

    def archive_files(self) -> list[tuple[str, bytes]]:
        with self.lock:
            calibration = self.stereo.calibration
            views = list(self.stereo.views)
            name = self.stereo.camera_name
        if calibration is None:
            return []
        files = [(f"{side}-{index:04d}.png", png(self.cv2, grey)) for index, view in enumerate(views)
                 for side, grey in (("left", view.left_grey), ("right", view.right_grey))]
        return [*files, ("left.yaml", ost_yaml(calibration.left, name + "/left").encode()),
                ("right.yaml", ost_yaml(calibration.right, name + "/right").encode()),
                ("ost.txt", (ost_txt(calibration.left, name + "/left")
                             + ost_txt(calibration.right, name + "/right")).encode())]

    def camera_infos(self) -> list[tuple[str, Any]]:
        with self.lock:
            calibration = self.stereo.calibration
        if calibration is None:
            return []
        return [(self.cameras[0], camera_info(calibration.left)), (self.cameras[1], camera_info(calibration.right))]
