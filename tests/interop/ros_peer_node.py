"""A real rospy node for interop tests (runs under /usr/bin/python3 with Debian's rospy).

It publishes std_msgs/String "hello N" on /chatter at 20 Hz, serves /set_flag (std_srvs/SetBool),
and prints "cached <value>" whenever rospy.get_param_cached('/cached') changes, so a test can see
the master's paramUpdate reach a real node.
"""

import rospy
from std_msgs.msg import String
from std_srvs.srv import SetBool, SetBoolResponse


def main():
    rospy.init_node("peer")
    pub = rospy.Publisher("chatter", String, queue_size=10)
    rospy.Service("set_flag", SetBool, lambda req: SetBoolResponse(success=req.data, message=f"flag {req.data}"))
    last = object()
    n = 0
    rate = rospy.Rate(20)
    print("ready", flush=True)
    while not rospy.is_shutdown():
        value = rospy.get_param_cached("/cached", None)
        if value != last:
            print(f"cached {value!r}", flush=True)
            last = value
        pub.publish(String(data=f"hello {n}"))
        n += 1
        try:
            rate.sleep()
        except rospy.ROSInterruptException:
            break


main()
