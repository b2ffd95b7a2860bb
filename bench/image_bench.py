"""The compressed transport's cost per frame: kame's compress/decompress of a 640x480 rgb8 camera
frame (through OpenCV and through Pillow) beside the same work done as compressed_image_transport
does it, with Debian's OpenCV under /usr/bin/python3 (RGB2BGR + imencode at quality 80 / png level
9; imdecode + BGR2RGB): Debian ships no compressed plugin to time directly.

CPU time per frame (time.process_time, best of --reps runs of --frames frames), so a busy machine
moves the figures less than wall time would. Run: .venv/bin/python bench/image_bench.py
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time
from collections.abc import Callable
from typing import Any

WIDTH, HEIGHT = 640, 480

DEBIAN = """
import json, sys, time
import cv2, numpy
from sensor_msgs.msg import Image
frames, reps = int(sys.argv[1]), int(sys.argv[2])
y, x = numpy.mgrid[0:480, 0:640]
rgb = numpy.dstack([(x ^ y) % 256, (y * 3) % 256, (x * 7 + y) % 256]).astype(numpy.uint8)
image = Image(height=480, width=640, encoding="rgb8", step=1920, data=rgb.tobytes())
params = {".jpg": [cv2.IMWRITE_JPEG_QUALITY, 80], ".png": [cv2.IMWRITE_PNG_COMPRESSION, 9]}
def encode(ext):  # compressed_image_transport's publisher: to bgr8, then imencode
    pixels = numpy.frombuffer(image.data, numpy.uint8).reshape(image.height, image.width, 3)
    return cv2.imencode(ext, cv2.cvtColor(pixels, cv2.COLOR_RGB2BGR), params[ext])[1].tobytes()
def decode(data):  # its subscriber: imdecode, then back to rgb8
    return cv2.cvtColor(cv2.imdecode(numpy.frombuffer(data, numpy.uint8), cv2.IMREAD_UNCHANGED),
                        cv2.COLOR_BGR2RGB).tobytes()
def best(work):
    times = []
    for _ in range(reps):
        start = time.process_time()
        for _ in range(frames):
            work()
        times.append((time.process_time() - start) / frames)
    return min(times)
result = {}
for ext in (".jpg", ".png"):
    data = encode(ext)
    result[ext] = [best(lambda: encode(ext)), best(lambda: decode(data))]
print(json.dumps(result))
"""


def best(work: Callable[[], Any], frames: int, reps: int) -> float:
    times = []
    for _ in range(reps):
        start = time.process_time()
        for _ in range(frames):
            work()
        times.append((time.process_time() - start) / frames)
    return min(times)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--frames", type=int, default=30)
    parser.add_argument("--reps", type=int, default=5)
    args = parser.parse_args()

    import numpy
    from kame.image_transport.compressed import OpenCVCodec, PillowCodec, Settings, compress, decompress, from_array
    from PIL import Image as PilImage
    from std_msgs.msg import Header

    y, x = numpy.mgrid[0:HEIGHT, 0:WIDTH]
    rgb = numpy.dstack([(x ^ y) % 256, (y * 3) % 256, (x * 7 + y) % 256]).astype(numpy.uint8)
    image = from_array(rgb, "rgb8", Header())
    codecs: dict[str, Any] = {"pillow": PillowCodec(PilImage)}
    try:
        import cv2

        codecs["opencv"] = OpenCVCodec(cv2)
    except ImportError:
        print("OpenCV is not installed: kame (opencv) is left out", file=sys.stderr)
    print(f"# {WIDTH}x{HEIGHT} rgb8, CPU ms per frame (best of {args.reps} x {args.frames}); "
          f"load average {os.getloadavg()[0]:.2f}")
    print(f"{'':24} {'jpeg encode':>12} {'jpeg decode':>12} {'png encode':>12} {'png decode':>12}")
    for name, codec in codecs.items():
        row = []
        for fmt in ("jpeg", "png"):
            settings = Settings(format=fmt)
            msg = compress(image, settings, codec)
            row += [best(lambda: compress(image, settings, codec), args.frames, args.reps),  # noqa: B023
                    best(lambda: decompress(msg, codec), args.frames, args.reps)]  # noqa: B023
        print(f"{'kame (' + name + ')':24}" + "".join(f" {t * 1000:12.2f}" for t in row))
    debian = subprocess.run(["/usr/bin/python3", "-c", DEBIAN, str(args.frames), str(args.reps)],
                            capture_output=True, text=True,
                            env={k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VIRTUAL_ENV")})
    if debian.returncode != 0:
        print(f"Debian's cv_bridge did not run: {debian.stderr.strip().splitlines()[-1:]}", file=sys.stderr)
        return
    figures = json.loads(debian.stdout)
    row = figures[".jpg"] + figures[".png"]
    print(f"{'Debian OpenCV (C++ path)':24}" + "".join(f" {t * 1000:12.2f}" for t in row))


if __name__ == "__main__":
    main()
