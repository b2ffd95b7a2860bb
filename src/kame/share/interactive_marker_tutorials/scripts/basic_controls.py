#!/usr/bin/env python3
# mypy: ignore-errors
# The interactive marker tutorials' basic_controls: markers with every kind of control (6-DOF
# fixed and rotating, 3-D, random axes, view facing, quadrocopter, chess piece, pan/tilt, a menu,
# a button, one on a moving frame), each change logged. Shown in rviz's InteractiveMarkers
# display on /basic_controls/update, fixed frame base_link.
import copy
import math
from random import random

import rospy
import tf
from geometry_msgs.msg import Point
from interactive_markers.interactive_marker_server import InteractiveMarkerServer
from interactive_markers.menu_handler import MenuHandler
from visualization_msgs.msg import InteractiveMarker, InteractiveMarkerControl, InteractiveMarkerFeedback, Marker

server = None
menu_handler = MenuHandler()
br = None
counter = 0


def frameCallback(msg):
    global counter
    time = rospy.Time.now()
    br.sendTransform((0, 0, math.sin(counter / 140.0) * 2.0), (0, 0, 0, 1.0), time, "moving_frame", "base_link")
    counter += 1


def processFeedback(feedback):
    s = "Feedback from marker '" + feedback.marker_name
    s += "' / control '" + feedback.control_name + "'"
    mp = ""
    if feedback.mouse_point_valid:
        mp = " at " + str(feedback.mouse_point.x) + ", " + str(feedback.mouse_point.y)
        mp += ", " + str(feedback.mouse_point.z) + " in frame " + feedback.header.frame_id
    if feedback.event_type == InteractiveMarkerFeedback.BUTTON_CLICK:
        rospy.loginfo(s + ": button click" + mp + ".")
    elif feedback.event_type == InteractiveMarkerFeedback.MENU_SELECT:
        rospy.loginfo(s + ": menu item " + str(feedback.menu_entry_id) + " clicked" + mp + ".")
    elif feedback.event_type == InteractiveMarkerFeedback.POSE_UPDATE:
        p, o = feedback.pose.position, feedback.pose.orientation
        rospy.loginfo(s + ": pose changed")
        rospy.loginfo("position = %s, %s, %s; orientation = %s, %s, %s, %s; frame: %s time: %s sec, %s nsec",
                      p.x, p.y, p.z, o.w, o.x, o.y, o.z, feedback.header.frame_id,
                      feedback.header.stamp.secs, feedback.header.stamp.nsecs)
    elif feedback.event_type == InteractiveMarkerFeedback.MOUSE_DOWN:
        rospy.loginfo(s + ": mouse down" + mp + ".")
    elif feedback.event_type == InteractiveMarkerFeedback.MOUSE_UP:
        rospy.loginfo(s + ": mouse up" + mp + ".")
    server.applyChanges()


def alignMarker(feedback):
    pose = feedback.pose
    pose.position.x = round(pose.position.x - 0.5) + 0.5
    pose.position.y = round(pose.position.y - 0.5) + 0.5
    rospy.loginfo(feedback.marker_name + ": aligning position = %s, %s, %s to %s, %s, %s",
                  feedback.pose.position.x, feedback.pose.position.y, feedback.pose.position.z,
                  pose.position.x, pose.position.y, pose.position.z)
    server.setPose(feedback.marker_name, pose)
    server.applyChanges()


def rand(min_, max_):
    return min_ + random() * (max_ - min_)


def makeBox(msg):
    marker = Marker()
    marker.type = Marker.CUBE
    marker.scale.x = msg.scale * 0.45
    marker.scale.y = msg.scale * 0.45
    marker.scale.z = msg.scale * 0.45
    marker.color.r = 0.5
    marker.color.g = 0.5
    marker.color.b = 0.5
    marker.color.a = 1.0
    return marker


def makeBoxControl(msg):
    control = InteractiveMarkerControl()
    control.always_visible = True
    control.markers.append(makeBox(msg))
    msg.controls.append(control)
    return control


def normalizeQuaternion(quaternion_msg):
    norm = quaternion_msg.x ** 2 + quaternion_msg.y ** 2 + quaternion_msg.z ** 2 + quaternion_msg.w ** 2
    s = norm ** (-0.5)
    quaternion_msg.x *= s
    quaternion_msg.y *= s
    quaternion_msg.z *= s
    quaternion_msg.w *= s


def axisControl(name, w, x, y, z, mode, fixed):
    control = InteractiveMarkerControl()
    control.orientation.w, control.orientation.x, control.orientation.y, control.orientation.z = w, x, y, z
    normalizeQuaternion(control.orientation)
    control.name = name
    control.interaction_mode = mode
    if fixed:
        control.orientation_mode = InteractiveMarkerControl.FIXED
    return control


def make6DofMarker(fixed, interaction_mode, position, show_6dof=False):
    int_marker = InteractiveMarker()
    int_marker.header.frame_id = "base_link"
    int_marker.pose.position = position
    int_marker.scale = 1
    int_marker.name = "simple_6dof"
    int_marker.description = "Simple 6-DOF Control"

    makeBoxControl(int_marker)
    int_marker.controls[0].interaction_mode = interaction_mode

    if fixed:
        int_marker.name += "_fixed"
        int_marker.description += "\n(fixed orientation)"

    if interaction_mode != InteractiveMarkerControl.NONE:
        control_modes_dict = {
            InteractiveMarkerControl.MOVE_3D: "MOVE_3D",
            InteractiveMarkerControl.ROTATE_3D: "ROTATE_3D",
            InteractiveMarkerControl.MOVE_ROTATE_3D: "MOVE_ROTATE_3D"}
        int_marker.name += "_" + control_modes_dict[interaction_mode]
        int_marker.description = "3D Control"
        if show_6dof:
            int_marker.description += " + 6-DOF controls"
        int_marker.description += "\n" + control_modes_dict[interaction_mode]

    if show_6dof:
        for name, axis in (("x", (1, 1, 0, 0)), ("z", (1, 0, 1, 0)), ("y", (1, 0, 0, 1))):
            for kind, mode in (("rotate_", InteractiveMarkerControl.ROTATE_AXIS),
                               ("move_", InteractiveMarkerControl.MOVE_AXIS)):
                int_marker.controls.append(axisControl(kind + name, *axis, mode, fixed))

    server.insert(int_marker, processFeedback)
    menu_handler.apply(server, int_marker.name)


def makeRandomDofMarker(position):
    int_marker = InteractiveMarker()
    int_marker.header.frame_id = "base_link"
    int_marker.pose.position = position
    int_marker.scale = 1
    int_marker.name = "6dof_random_axes"
    int_marker.description = "6-DOF\n(Arbitrary Axes)"

    makeBoxControl(int_marker)

    for _ in range(3):
        w, x, y, z = rand(-1, 1), rand(-1, 1), rand(-1, 1), rand(-1, 1)
        int_marker.controls.append(axisControl("", w, x, y, z, InteractiveMarkerControl.ROTATE_AXIS, False))
        int_marker.controls.append(axisControl("", w, x, y, z, InteractiveMarkerControl.MOVE_AXIS, False))

    server.insert(int_marker, processFeedback)


def makeViewFacingMarker(position):
    int_marker = InteractiveMarker()
    int_marker.header.frame_id = "base_link"
    int_marker.pose.position = position
    int_marker.scale = 1
    int_marker.name = "view_facing"
    int_marker.description = "View Facing 6-DOF"

    # make a control that rotates around the view axis
    control = InteractiveMarkerControl()
    control.orientation_mode = InteractiveMarkerControl.VIEW_FACING
    control.interaction_mode = InteractiveMarkerControl.ROTATE_AXIS
    control.orientation.w = 1
    control.name = "rotate"
    int_marker.controls.append(control)

    # create a box in the center which should not be view facing,
    # but move in the camera plane.
    control = InteractiveMarkerControl()
    control.orientation_mode = InteractiveMarkerControl.VIEW_FACING
    control.interaction_mode = InteractiveMarkerControl.MOVE_PLANE
    control.independent_marker_orientation = True
    control.name = "move"
    control.markers.append(makeBox(int_marker))
    control.always_visible = True
    int_marker.controls.append(control)

    server.insert(int_marker, processFeedback)


def makeQuadrocopterMarker(position):
    int_marker = InteractiveMarker()
    int_marker.header.frame_id = "base_link"
    int_marker.pose.position = position
    int_marker.scale = 1
    int_marker.name = "quadrocopter"
    int_marker.description = "Quadrocopter"

    makeBoxControl(int_marker)
    int_marker.controls.append(axisControl("", 1, 0, 1, 0, InteractiveMarkerControl.MOVE_ROTATE, False))
    int_marker.controls.append(axisControl("", 1, 0, 1, 0, InteractiveMarkerControl.MOVE_AXIS, False))

    server.insert(int_marker, processFeedback)


def makeChessPieceMarker(position):
    int_marker = InteractiveMarker()
    int_marker.header.frame_id = "base_link"
    int_marker.pose.position = position
    int_marker.scale = 1
    int_marker.name = "chess_piece"
    int_marker.description = "Chess Piece\n(2D Move + Alignment)"

    control = axisControl("", 1, 0, 1, 0, InteractiveMarkerControl.MOVE_PLANE, False)
    int_marker.controls.append(copy.deepcopy(control))

    # make a box which also moves in the plane
    control.markers.append(makeBox(int_marker))
    control.always_visible = True
    int_marker.controls.append(control)

    # we want to use our special callback function
    server.insert(int_marker, processFeedback)

    # set different callback for POSE_UPDATE feedback
    server.setCallback(int_marker.name, alignMarker, InteractiveMarkerFeedback.POSE_UPDATE)


def makePanTiltMarker(position):
    int_marker = InteractiveMarker()
    int_marker.header.frame_id = "base_link"
    int_marker.pose.position = position
    int_marker.scale = 1
    int_marker.name = "pan_tilt"
    int_marker.description = "Pan / Tilt"

    makeBoxControl(int_marker)
    int_marker.controls.append(axisControl("", 1, 0, 1, 0, InteractiveMarkerControl.ROTATE_AXIS, True))
    int_marker.controls.append(axisControl("", 1, 0, 0, 1, InteractiveMarkerControl.ROTATE_AXIS, False))

    server.insert(int_marker, processFeedback)


def makeMenuMarker(position):
    int_marker = InteractiveMarker()
    int_marker.header.frame_id = "base_link"
    int_marker.pose.position = position
    int_marker.scale = 1
    int_marker.name = "context_menu"
    int_marker.description = "Context Menu\n(Right Click)"

    # make one control using default visuals
    control = InteractiveMarkerControl()
    control.interaction_mode = InteractiveMarkerControl.MENU
    control.description = "Options"
    control.name = "menu_only_control"
    int_marker.controls.append(copy.deepcopy(control))

    # make one control showing a box
    marker = makeBox(int_marker)
    control.markers.append(marker)
    control.always_visible = True
    int_marker.controls.append(control)

    server.insert(int_marker, processFeedback)
    menu_handler.apply(server, int_marker.name)


def makeButtonMarker(position):
    int_marker = InteractiveMarker()
    int_marker.header.frame_id = "base_link"
    int_marker.pose.position = position
    int_marker.scale = 1
    int_marker.name = "button"
    int_marker.description = "Button\n(Left Click)"

    control = InteractiveMarkerControl()
    control.interaction_mode = InteractiveMarkerControl.BUTTON
    control.name = "button_control"

    marker = makeBox(int_marker)
    control.markers.append(marker)
    control.always_visible = True
    int_marker.controls.append(control)

    server.insert(int_marker, processFeedback)


def makeMovingMarker(position):
    int_marker = InteractiveMarker()
    int_marker.header.frame_id = "moving_frame"
    int_marker.pose.position = position
    int_marker.scale = 1
    int_marker.name = "moving"
    int_marker.description = "Marker Attached to a\nMoving Frame"

    control = axisControl("", 1, 1, 0, 0, InteractiveMarkerControl.ROTATE_AXIS, False)
    int_marker.controls.append(copy.deepcopy(control))

    control.interaction_mode = InteractiveMarkerControl.MOVE_PLANE
    control.always_visible = True
    control.markers.append(makeBox(int_marker))
    int_marker.controls.append(control)

    server.insert(int_marker, processFeedback)


if __name__ == "__main__":
    rospy.init_node("basic_controls")
    br = tf.TransformBroadcaster()

    # create a timer to update the published transforms
    rospy.Timer(rospy.Duration(0.01), frameCallback)

    server = InteractiveMarkerServer("basic_controls")

    menu_handler.insert("First Entry", callback=processFeedback)
    menu_handler.insert("Second Entry", callback=processFeedback)
    sub_menu_handle = menu_handler.insert("Submenu")
    menu_handler.insert("First Entry", parent=sub_menu_handle, callback=processFeedback)
    menu_handler.insert("Second Entry", parent=sub_menu_handle, callback=processFeedback)

    position = Point(-3, 3, 0)
    make6DofMarker(False, InteractiveMarkerControl.NONE, position, True)
    position = Point(0, 3, 0)
    make6DofMarker(True, InteractiveMarkerControl.NONE, position, True)
    position = Point(3, 3, 0)
    makeRandomDofMarker(position)
    position = Point(-3, 0, 0)
    make6DofMarker(False, InteractiveMarkerControl.ROTATE_3D, position, False)
    position = Point(0, 0, 0)
    make6DofMarker(False, InteractiveMarkerControl.MOVE_ROTATE_3D, position, True)
    position = Point(3, 0, 0)
    make6DofMarker(False, InteractiveMarkerControl.MOVE_3D, position, False)
    position = Point(-3, -3, 0)
    makeViewFacingMarker(position)
    position = Point(0, -3, 0)
    makeQuadrocopterMarker(position)
    position = Point(3, -3, 0)
    makeChessPieceMarker(position)
    position = Point(-3, -6, 0)
    makePanTiltMarker(position)
    position = Point(0, -6, 0)
    makeMenuMarker(position)
    position = Point(3, -6, 0)
    makeButtonMarker(position)
    position = Point(0, 0, 0)
    makeMovingMarker(position)

    server.applyChanges()

    rospy.spin()
