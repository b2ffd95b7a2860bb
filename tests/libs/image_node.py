"""A ROS node for image_transport's live tests, run by kame's or Debian's interpreter.

`pub <encoding>`: publishes pattern(<encoding>) on /camera/image_raw at 20 Hz.
`pub-png`: publishes that rgb8 pattern as Debian's cv_bridge compresses it (format "png") on
/camera/image_raw/compressed.
`sub <topic> <Image|CompressedImage> [<count>]`: waits for <count> messages (1 by default) and
prints the last as a JSON line (its pixels or compressed bytes in base64).
`cvsub <topic>`: decodes one CompressedImage with cv_bridge's compressed_imgmsg_to_cv2 and prints
the array's shape, type and bytes.
"""

import base64
import json
import sys

import rospy
from sensor_msgs.msg import CompressedImage, Image

WIDTH, HEIGHT = 24, 16


def pattern(encoding: str) -> bytes:
    """Smooth rows and columns (kind to jpeg): red across, green down, blue constant."""
    pixels = []
    for y in range(HEIGHT):
        for x in range(WIDTH):
            red, green, blue = 40 + x * 8, 30 + y * 12, 128
            if encoding == "rgb8":
                pixels += [red, green, blue]
            elif encoding == "bgr8":
                pixels += [blue, green, red]
            elif encoding == "mono8":
                pixels.append(red)
            elif encoding == "mono16":
                pixels += list((red * 200 + y).to_bytes(2, "little"))
            else:  # 32FC1: what compressed_image_transport refuses
                pixels += [0, 0, 128, 63]
    return bytes(pixels)


def publish(encoding: str) -> None:
    rospy.init_node("image_pub")
    pub = rospy.Publisher("/camera/image_raw", Image, queue_size=1)
    data = pattern(encoding)
    image = Image(height=HEIGHT, width=WIDTH, encoding=encoding, step=len(data) // HEIGHT, data=data)
    image.header.frame_id = "camera"
    rate = rospy.Rate(20)
    while not rospy.is_shutdown():
        image.header.stamp = rospy.Time.now()
        pub.publish(image)
        rate.sleep()


def publish_png() -> None:
    import numpy

    from cv_bridge import CvBridge

    rospy.init_node("image_pub")
    pub = rospy.Publisher("/camera/image_raw/compressed", CompressedImage, queue_size=1)
    bgr = numpy.frombuffer(pattern("bgr8"), numpy.uint8).reshape(HEIGHT, WIDTH, 3)
    message = CvBridge().cv2_to_compressed_imgmsg(bgr, "png")
    rate = rospy.Rate(20)
    while not rospy.is_shutdown():
        pub.publish(message)
        rate.sleep()


def subscribe(topic: str, type_name: str, count: int) -> None:
    rospy.init_node("image_sub", anonymous=True)
    cls = Image if type_name == "Image" else CompressedImage
    received = []

    def got(message: object) -> None:
        received.append(message)
        if len(received) == count:
            rospy.signal_shutdown("done")

    rospy.Subscriber(topic, cls, got, queue_size=1)
    print("subscribed", flush=True)
    rospy.spin()
    message = received[-1]
    fields = {"frame_id": message.header.frame_id, "data": base64.b64encode(bytes(message.data)).decode()}
    if cls is Image:
        fields.update(encoding=message.encoding, width=message.width, height=message.height, step=message.step)
    else:
        fields.update(format=message.format)
    print(json.dumps(fields), flush=True)


def cv_subscribe(topic: str) -> None:
    from cv_bridge import CvBridge

    rospy.init_node("image_cvsub", anonymous=True)
    message = rospy.wait_for_message(topic, CompressedImage, timeout=60)
    array = CvBridge().compressed_imgmsg_to_cv2(message)
    print(json.dumps({"format": message.format, "shape": list(array.shape), "dtype": str(array.dtype),
                      "data": base64.b64encode(array.tobytes()).decode()}), flush=True)


if __name__ == "__main__":
    command = sys.argv[1]
    if command == "pub":
        publish(sys.argv[2])
    elif command == "pub-png":
        publish_png()
    elif command == "sub":
        subscribe(sys.argv[2], sys.argv[3], int(sys.argv[4]) if len(sys.argv) > 4 else 1)
    else:
        cv_subscribe(sys.argv[2])
