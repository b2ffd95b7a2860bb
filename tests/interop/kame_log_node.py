"""A kame rospy node for the rosout tests: logs "warn N" from `work` at 10 Hz and publishes /lt.

Runs with kame's interpreter (`python kame_log_node.py`); prints "ready" once it is up.
"""

from __future__ import annotations

import rospy
from std_msgs.msg import String


def work(pub: rospy.Publisher, n: int) -> None:
    rospy.logwarn("warn %d", n)
    pub.publish(String(data=str(n)))


def main() -> None:
    rospy.init_node("lognode")
    pub = rospy.Publisher("lt", String, queue_size=1)
    rate = rospy.Rate(10)
    print("ready", flush=True)
    n = 0
    while not rospy.is_shutdown():
        work(pub, n)
        n += 1
        try:
            rate.sleep()
        except rospy.ROSInterruptException:
            break


if __name__ == "__main__":
    main()
