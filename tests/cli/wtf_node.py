"""A kame rospy node for the roswtf tests: publishes and subscribes what it is told.

`python wtf_node.py [--pub TOPIC=TYPE]... [--sub TOPIC=TYPE]... [__name:=x]`, TYPE like
std_msgs/String. Publishes nothing (registration is what roswtf looks at); prints "ready" once
everything is registered, then spins.
"""

from __future__ import annotations

import argparse
import importlib

import rospy


def message_class(type_name: str) -> type:
    package, name = type_name.split("/")
    return getattr(importlib.import_module(f"{package}.msg"), name)  # type: ignore[no-any-return]


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--pub", action="append", default=[])
    parser.add_argument("--sub", action="append", default=[])
    args = parser.parse_args(rospy.myargv()[1:])
    rospy.init_node("wtf_node")
    keep: list[object] = []
    for spec in args.pub:
        topic, type_name = spec.split("=")
        keep.append(rospy.Publisher(topic, message_class(type_name), queue_size=1))
    for spec in args.sub:
        topic, type_name = spec.split("=")
        keep.append(rospy.Subscriber(topic, message_class(type_name), lambda msg: None))
    print("ready", flush=True)
    rospy.spin()


if __name__ == "__main__":
    main()
