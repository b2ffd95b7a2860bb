"""Publishes the synthetic chessboard views (tests/camera/synthetic.py) on /camera/image_raw as
mono8 Images at 10 Hz, every view once a round in an order shuffled anew each round (plain rospy,
as a user's camera). Shuffled because the calibrator drops the frames that come while it looks
at one: in a fixed order, a calibrator that takes two frames' time sees every other view and
nothing else, round after round (on a busy machine, never the whole range of sizes).
With `stereo`: the views of a pair 0.12 m apart on /stereo/left/image_raw and
/stereo/right/image_raw, each pair with one stamp."""

import random
import sys

import rospy
from sensor_msgs.msg import Image
from tests.camera.synthetic import BASELINE, Renderer, poses, stereo_poses


def image(view, stamp):  # type: ignore[no-untyped-def]
    message = Image(height=view.shape[0], width=view.shape[1], encoding="mono8", step=view.shape[1],
                    data=view.tobytes())
    message.header.stamp = stamp
    return message


if __name__ == "__main__":
    renderer = Renderer()
    stereo = sys.argv[1:] == ["stereo"]
    if stereo:
        views = [(renderer.view(rvec, tvec), renderer.view(rvec, (tvec[0] - BASELINE, tvec[1], tvec[2])))
                 for rvec, tvec in stereo_poses()]
        topics = ["/stereo/left/image_raw", "/stereo/right/image_raw"]
    else:
        views = [(renderer.view(*pose),) for pose in poses()]
        topics = ["/camera/image_raw"]
    rospy.init_node("views")
    publishers = [rospy.Publisher(topic, Image, queue_size=1) for topic in topics]
    print(f"publishing {len(views)} views", flush=True)
    rate = rospy.Rate(10)
    shuffle = random.Random(0)  # the same rounds every run
    order: list[int] = []
    while not rospy.is_shutdown():
        if not order:
            order = list(range(len(views)))
            shuffle.shuffle(order)
        stamp = rospy.Time.now()
        for publisher, view in zip(publishers, views[order.pop()], strict=True):
            publisher.publish(image(view, stamp))
        rate.sleep()
