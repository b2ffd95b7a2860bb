"""Publishes the synthetic chessboard views (tests/camera/synthetic.py) on /camera/image_raw as
mono8 Images, one after the other and round again, at 10 Hz (plain rospy, as a user's camera)."""

import rospy
from sensor_msgs.msg import Image
from tests.camera.synthetic import Renderer, poses

if __name__ == "__main__":
    renderer = Renderer()
    views = [renderer.view(*pose) for pose in poses()]
    rospy.init_node("views")
    publisher = rospy.Publisher("/camera/image_raw", Image, queue_size=1)
    print(f"publishing {len(views)} views", flush=True)
    rate = rospy.Rate(10)
    number = 0
    while not rospy.is_shutdown():
        view = views[number % len(views)]
        number += 1
        image = Image(height=view.shape[0], width=view.shape[1], encoding="mono8", step=view.shape[1],
                      data=view.tobytes())
        image.header.stamp = rospy.Time.now()
        publisher.publish(image)
        rate.sleep()
