"""A kame node for the tool modules' tests: publishes /chatter (std_msgs/String) and
/pose (geometry_msgs/PoseStamped) at 50 Hz and serves /add_two_ints (rospy_tutorials/AddTwoInts)."""

import rospy
from geometry_msgs.msg import PoseStamped
from rospy_tutorials.srv import AddTwoInts, AddTwoIntsResponse
from std_msgs.msg import String

rospy.init_node("tools_node")
chatter = rospy.Publisher("chatter", String, queue_size=10)
pose = rospy.Publisher("pose", PoseStamped, queue_size=10)
rospy.Service("add_two_ints", AddTwoInts, lambda req: AddTwoIntsResponse(req.a + req.b))
print("ready", flush=True)
rate = rospy.Rate(50)
count = 0
while not rospy.is_shutdown():
    chatter.publish(String(data=f"hello {count}"))
    msg = PoseStamped()
    msg.header.stamp = rospy.Time.now()
    msg.pose.position.x = count
    pose.publish(msg)
    count += 1
    rate.sleep()
