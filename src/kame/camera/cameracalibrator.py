"""camera_calibration's cameracalibrator.py (monocular): `rosrun camera_calibration
cameracalibrator.py --size 8x6 --square 0.108 image:=/usb_cam/image_raw camera:=/usb_cam`.

Each image of `image` goes to the calibrator (kame.camera.calibrator) on a worker thread that
takes the newest one; the window shows the result with the X, Y, Size and Skew bars. CALIBRATE
computes the calibration and prints it; SAVE writes /tmp/calibrationdata.tar.gz ($TMPDIR if
set; the kept views as left-NNNN.png, ost.yaml, ost.txt); COMMIT sends it to `camera`/set_camera_info and quits
when the camera stored it. q or Esc quits, s saves the display as /tmp/dumpN.png.
"""

from __future__ import annotations

import argparse
import io
import os
import sys
import tarfile
import tempfile
import threading
from collections.abc import Sequence
from typing import Any

import numpy as np

from kame.camera.calibration_display import button_at, render
from kame.camera.calibration_report import camera_info, ost_txt, ost_yaml, report
from kame.camera.calibrator import Board, MonoCalibrator, Options, linear_error
from kame.camera.image_feed import subscribe_image
from kame.camera.opencv import OpenCVMissing, cv2_for
from kame.camera.pictures import PictureError, to_bgr
from kame.client import core, log
from kame.client.core import get_namespace, resolve_name
from kame.client.errors import ROSException
from kame.client.process import init_node, myargv
from kame.client.services import ServiceException, ServiceProxy, wait_for_service
from sensor_msgs.srv import SetCameraInfo


def tarball_path() -> str:
    """Where SAVE writes: /tmp/calibrationdata.tar.gz as upstream, in $TMPDIR when that is set
    (so two calibrations, or two test runs, at once each keep their own)."""
    return os.path.join(tempfile.gettempdir(), "calibrationdata.tar.gz")


def parse_options(args: list[str]) -> argparse.Namespace:
    parser = argparse.ArgumentParser(prog="cameracalibrator.py",
                                     usage="%(prog)s --size SIZE1 --square SQUARE1 [ --size SIZE2 --square SQUARE2 ]")
    parser.add_argument("-c", "--camera_name", default="narrow_stereo", help="name of the camera to appear in the "
                        "calibration file")
    parser.add_argument("-s", "--size", action="append", default=[], help="chessboard size as NxM, counting "
                        "interior corners (e.g. a standard chessboard is 7x7)")
    parser.add_argument("-q", "--square", action="append", default=[], type=float,
                        help="chessboard square size in meters")
    parser.add_argument("-p", "--pattern", default="chessboard", choices=["chessboard"],
                        help="calibration pattern to detect (kame: chessboard)")
    parser.add_argument("--approximate", type=float, default=0.0, help="allow specified slop (in seconds) when "
                        "pairing images from unsynchronized stereo cameras")
    parser.add_argument("--no-service-check", action="store_true", help="disable check for set_camera_info services "
                        "at startup")
    parser.add_argument("--queue-size", type=int, default=1, help="image queue size")
    parser.add_argument("--fix-principal-point", action="store_true", help="for pinhole, fix the principal point at "
                        "the image center")
    parser.add_argument("--fix-aspect-ratio", action="store_true", help="for pinhole, enforce focal lengths (fx, fy) "
                        "are equal")
    parser.add_argument("--zero-tangent-dist", action="store_true", help="for pinhole, set tangential distortion "
                        "coefficients (p1, p2) to zero")
    parser.add_argument("-k", "--k-coefficients", type=int, default=2, help="for pinhole, number of radial distortion "
                        "coefficients to use (up to 6, default %(default)s)")
    parser.add_argument("--max-chessboard-speed", type=float, default=-1.0, help="Do not use samples where the "
                        "calibration pattern is moving faster than this speed in px/frame. Set to eg. 0.5 for rolling "
                        "shutter cameras.")
    options = parser.parse_args(args)
    if not options.size or len(options.size) != len(options.square):
        parser.error("You must specify one or more chessboards as pairs of --size and --square options.")
    if not 0 <= options.k_coefficients <= 6:
        parser.error("-k takes 0 to 6 radial distortion coefficients")
    return options


class CalibrationNode:
    def __init__(self, cv2: Any, calibrator: MonoCalibrator, camera: str) -> None:
        self.cv2 = cv2
        self.calibrator = calibrator
        self.camera = camera
        self.lock = threading.Lock()  # the calibrator, shared by the worker and the window's clicks
        self.newest: Any = None
        self.arrived = threading.Condition()
        self.display: np.ndarray | None = None
        self.display_lock = threading.Lock()
        self.last_display: np.ndarray | None = None
        self.picture_width = 0
        self.on_display: Any = None
        self.stopping = False
        self.dumps = 0
        self.worker = threading.Thread(target=self._work, name="calibrator")

    def start(self, topics: list[str], queue_size: int) -> None:
        """Subscribes to the camera's image topic (a stereo node: the left and the right one)."""
        self.subscribers = [subscribe_image(topic, "raw", self._arrive, queue_size=queue_size) for topic in topics]
        self.worker.start()

    def stop(self) -> None:
        with self.arrived:
            self.stopping = True
            self.arrived.notify()
        self.worker.join()

    def _arrive(self, image: Any) -> None:
        with self.arrived:
            self.newest = image
            self.arrived.notify()

    def _work(self) -> None:
        while True:
            with self.arrived:
                while self.newest is None and not self.stopping:
                    self.arrived.wait()
                if self.stopping:
                    return
                message, self.newest = self.newest, None
            self.handle_message(message)

    def handle_message(self, image: Any) -> None:
        try:
            picture = to_bgr(image, "camera_calibration")
        except PictureError as exc:
            log.emit_throttle(5.0, log.ERROR, "%s", (exc,))
            return
        self.show(self.process(picture))

    def process(self, picture: np.ndarray) -> np.ndarray:
        cv2, board = self.cv2, self.calibrator.board
        with self.lock:
            try:
                detection, kept = self.calibrator.handle(picture)
            except ValueError as exc:
                log.emit_throttle(5.0, log.ERROR, "%s", (exc,))
                return self.last_display if self.last_display is not None else picture
            calibrated = self.calibrator.calibration is not None
            shown = self.calibrator.rectify(picture) if calibrated else picture
            scrib = cv2.cvtColor(shown, cv2.COLOR_GRAY2BGR) if shown.ndim == 2 else shown.copy()
            error: float | None = None
            corners = detection.corners
            if corners is not None and calibrated:
                corners = self.calibrator.rectified_corners(corners)
                error = linear_error(corners, board)
            if corners is not None:
                cv2.drawChessboardCorners(scrib, (board.cols, board.rows), corners.astype(np.float32), True)
            if kept and detection.params is not None:
                p_x, p_y, p_size, skew = detection.params
                print(f"*** Added sample {len(self.calibrator.views)}, p_x = {p_x:.3f}, p_y = {p_y:.3f}, "
                      f"p_size = {p_size:.3f}, skew = {skew:.3f}", flush=True)
            self.picture_width = scrib.shape[1]
            return render(cv2, scrib, self.calibrator.progress(), self.calibrator.goodenough, calibrated,
                          [("lin.", error)])

    def show(self, display: np.ndarray) -> None:
        with self.display_lock:
            was_empty = self.display is None
            self.display = self.last_display = display
        if was_empty and self.on_display is not None:
            self.on_display()

    def take_display(self) -> np.ndarray | None:
        with self.display_lock:
            display, self.display = self.display, None
        return display

    def click(self, x: int, y: int) -> None:
        with self.lock:
            calibrated = self.calibrator.calibration is not None
            button = button_at(x, y, self.picture_width, self.calibrator.goodenough, calibrated)
        if button == "CALIBRATE":
            self.calibrate()
        elif button == "SAVE":
            self.save()
        elif button == "COMMIT" and self.commit():
            core.signal_shutdown("Quit")

    def calibrate(self) -> None:
        print("**** Calibrating ****", flush=True)
        with self.lock:
            calibration = self.calibrator.calibrate()
            print("mono pinhole calibration...")
            print(report(calibration))
            print(ost_txt(calibration, self.calibrator.camera_name), flush=True)

    def archive_files(self) -> list[tuple[str, bytes]]:
        """What SAVE puts in the tarball: the kept views, ost.yaml and ost.txt."""
        with self.lock:
            calibration = self.calibrator.calibration
            views = [grey for _, _, grey in self.calibrator.views]
            name = self.calibrator.camera_name
        if calibration is None:
            return []
        return [*((f"left-{index:04d}.png", png(self.cv2, grey)) for index, grey in enumerate(views)),
                ("ost.yaml", ost_yaml(calibration, name).encode()), ("ost.txt", ost_txt(calibration, name).encode())]

    def save(self) -> None:
        files = self.archive_files()
        if not files:
            return
        tarball = tarball_path()
        with tarfile.open(tarball, "w:gz") as archive:
            for file_name, data in files:
                entry = tarfile.TarInfo(file_name)
                entry.size = len(data)
                archive.addfile(entry, io.BytesIO(data))
        print(f"('Wrote calibration data to', '{tarball}')", flush=True)

    def camera_infos(self) -> list[tuple[str, Any]]:
        """(camera namespace, CameraInfo) of each camera COMMIT sends to."""
        with self.lock:
            calibration = self.calibrator.calibration
        return [] if calibration is None else [(self.camera, camera_info(calibration))]

    def commit(self) -> bool:
        """set_camera_info on each camera; True when every one stored its calibration."""
        infos = self.camera_infos()
        for camera, info in infos:
            try:
                response = ServiceProxy(camera.rstrip("/") + "/set_camera_info", SetCameraInfo)(info)
            except (ServiceException, ROSException) as exc:
                log.emit(log.ERROR, "Service call failed: %s", (exc,))
                return False
            if not response.success:
                log.emit(log.ERROR, "Unable to set camera info for calibration. Failure message: %s",
                         (response.status_message,))
                return False
            print(response, flush=True)
        return bool(infos)

    def key(self, text: str) -> None:
        if text in ("q", "\x1b"):
            core.signal_shutdown("Quit")
        elif text == "s" and self.last_display is not None:
            name = f"/tmp/dump{self.dumps}.png"
            self.cv2.imwrite(name, self.last_display)
            print(f"Saved {name}", flush=True)
            self.dumps += 1


def remapped(name: str) -> str | None:
    """The name `name` resolves to when the command line remapped it, else None."""
    resolved = resolve_name(name)
    return None if resolved == get_namespace().rstrip("/") + "/" + name else resolved


def png(cv2: Any, grey: np.ndarray) -> bytes:
    return bytes(cv2.imencode(".png", grey)[1].data)


def check_service(camera: str) -> bool:
    name = f"{camera.rstrip('/')}/set_camera_info"
    print(f"Waiting for service {name} ...", flush=True)
    try:
        wait_for_service(name, 5)
    except ROSException:
        print("Service not found", flush=True)
        return False
    print("OK", flush=True)
    return True


def main(argv: Sequence[str] | None = None) -> int:
    argv = list(sys.argv if argv is None else argv)
    try:
        cv2 = cv2_for("camera_calibration")
        from PySide6.QtCore import QMetaObject, Qt
        from PySide6.QtWidgets import QApplication

        from kame.camera.calibration_window import CalibrationWindow
        from kame.qt_quit import quit_on_signals
    except OpenCVMissing as exc:
        sys.stderr.write(f"{exc}\n")
        return 1
    except ImportError as exc:
        sys.stderr.write(f"camera_calibration's window needs PySide6: pip install 'kame[gui]' ({exc})\n")
        return 1
    options = parse_options(myargv(argv)[1:])
    init_node("cameracalibrator", argv)
    board = Board.parse(options.size[0], options.square[0])
    calibrator = MonoCalibrator(board, Options(options.k_coefficients, options.fix_principal_point,
                                               options.fix_aspect_ratio, options.zero_tangent_dist,
                                               options.max_chessboard_speed), options.camera_name)
    stereo = remapped("left") is not None
    cameras = ["left_camera", "right_camera"] if stereo else ["camera"]
    for camera in cameras:  # upstream waits only for the cameras named on the command line
        name = remapped(camera)
        if not options.no_service_check and name is not None and not check_service(name):
            core.signal_shutdown("Quit")
            return 1
    app = QApplication.instance() or QApplication(["cameracalibrator"])
    quit_on_signals(app)
    if stereo:
        from kame.camera.stereo_calibration_node import StereoCalibrationNode
        from kame.camera.stereo_calibrator import StereoCalibrator

        pair = StereoCalibrator(calibrator.board, calibrator.options, calibrator.camera_name)
        node: CalibrationNode = StereoCalibrationNode(cv2, pair, (resolve_name("left_camera"),
                                                                 resolve_name("right_camera")), options.approximate)
    else:
        node = CalibrationNode(cv2, calibrator, resolve_name("camera"))
    window = CalibrationWindow(node.take_display, node.click, node.key)
    node.on_display = window.display_ready.emit
    core.on_shutdown(lambda *_: QMetaObject.invokeMethod(app, "quit", Qt.ConnectionType.QueuedConnection))
    node.start([resolve_name(topic) for topic in (("left", "right") if stereo else ("image",))], options.queue_size)
    window.show()
    try:
        with core.main_thread_waiting():
            app.exec()
    finally:
        node.stop()
        core.signal_shutdown("cameracalibrator closed")
    return 0
