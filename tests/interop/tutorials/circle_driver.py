#!/usr/bin/env python
# A parameterised node from the courses: drives a turtle in a circle with radius and speed from
# private parameters, and reports the poses it hears.
import rospy
from geometry_msgs.msg import Twist
from turtlesim.msg import Pose

def on_pose(pose):
    rospy.loginfo_throttle(0.2, "pose x=%.2f y=%.2f", pose.x, pose.y)

def main():
    rospy.init_node('circle_driver')
    speed = rospy.get_param('~speed', 1.0)
    radius = rospy.get_param('~radius', 2.0)
    rospy.loginfo("driving at %.1f m/s on a %.1f m circle", speed, radius)
    pub = rospy.Publisher('turtle1/cmd_vel', Twist, queue_size=1)
    rospy.Subscriber('turtle1/pose', Pose, on_pose)
    rate = rospy.Rate(20)
    while not rospy.is_shutdown():
        cmd = Twist()
        cmd.linear.x = speed
        cmd.angular.z = speed / radius
        pub.publish(cmd)
        rate.sleep()

if __name__ == '__main__':
    try:
        main()
    except rospy.ROSInterruptException:
        pass
