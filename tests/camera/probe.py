"""A ROS program for the camera tests (plain rospy, as a user's would be).

`images <topic> <count> <out.npz>`: waits for <count> sensor_msgs/Image messages, saves the first
and last pictures and every header stamp to <out.npz>, prints a JSON line with the encoding,
size, frame_id and the stamps' mean rate.
`info <topic>`: prints one sensor_msgs/CameraInfo as a JSON line.
"""

import json
import sys
import threading

import numpy

import rospy
from sensor_msgs.msg import CameraInfo, Image


def pixels(image: Image) -> numpy.ndarray:
    channels = {"rgb8": 3, "bgr8": 3, "mono8": 1}[image.encoding]
    rows = numpy.frombuffer(image.data, numpy.uint8).reshape(image.height, image.step)
    picture: numpy.ndarray = rows[:, :image.width * channels].reshape(image.height, image.width, channels).copy()
    return picture


def images(topic: str, count: int, out: str) -> None:
    got: list[Image] = []
    done = threading.Event()

    def take(image: Image) -> None:
        if len(got) < count:
            got.append(image)
        if len(got) == count:
            done.set()

    rospy.init_node("camera_probe", anonymous=True)
    rospy.on_shutdown(done.set)
    rospy.Subscriber(topic, Image, take, queue_size=count)
    done.wait()
    if len(got) < count:
        sys.exit(1)
    stamps = numpy.array([image.header.stamp.to_sec() for image in got])
    numpy.savez(out, first=pixels(got[0]), last=pixels(got[-1]), stamps=stamps)
    rate = (len(stamps) - 1) / (stamps[-1] - stamps[0]) if count > 1 else 0.0
    first = got[0]
    print(json.dumps({"encoding": first.encoding, "width": first.width, "height": first.height,
                      "frame_id": first.header.frame_id, "rate": rate}), flush=True)


def info(topic: str) -> None:
    rospy.init_node("camera_probe", anonymous=True)
    message = rospy.wait_for_message(topic, CameraInfo, timeout=30)
    print(json.dumps({"width": message.width, "height": message.height, "K": list(message.K),
                      "D": list(message.D), "frame_id": message.header.frame_id,
                      "distortion_model": message.distortion_model}), flush=True)


if __name__ == "__main__":
    if sys.argv[1] == "images":
        images(sys.argv[2], int(sys.argv[3]), sys.argv[4])
    else:
        info(sys.argv[2])
