#!/usr/bin/env python
# The rospy_tutorials AddTwoInts server (srv import before rospy, as in the tutorial).
from __future__ import print_function

from rospy_tutorials.srv import AddTwoInts,AddTwoIntsResponse
import rospy

def handle_add_two_ints(req):
    print("Returning [%s + %s = %s]"%(req.a, req.b, (req.a + req.b)), flush=True)
    return AddTwoIntsResponse(req.a + req.b)

def add_two_ints_server():
    rospy.init_node('add_two_ints_server')
    s = rospy.Service('add_two_ints', AddTwoInts, handle_add_two_ints)
    print("Ready to add two ints.", flush=True)
    rospy.spin()

if __name__ == "__main__":
    add_two_ints_server()
