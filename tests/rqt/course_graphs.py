"""The graphs the courses show in rqt_graph, as the master and the nodes' bus info describe them:
each is a list of (publisher, topic, subscriber) connections."""

from __future__ import annotations

from kame.rqt.graph_model import GraphSnapshot, snapshot_from

Links = list[tuple[str, str, str]]

LESSON_ONE: Links = [("/teleop_turtle", "/turtle1/cmd_vel", "/turtlesim")]

DRAW_SQUARE: Links = [("/draw_square", "/turtle1/cmd_vel", "/turtlesim"),
                      ("/turtlesim", "/turtle1/pose", "/draw_square")]

TURTLE_TF2: Links = [
    ("/teleop", "/turtle1/cmd_vel", "/sim"),
    ("/sim", "/turtle1/pose", "/turtle1_tf2_broadcaster"),
    ("/sim", "/turtle2/pose", "/turtle2_tf2_broadcaster"),
    ("/turtle1_tf2_broadcaster", "/tf", "/listener"),
    ("/turtle2_tf2_broadcaster", "/tf", "/listener"),
    ("/listener", "/turtle2/cmd_vel", "/sim"),
]

NAVIGATION: Links = [
    *(("/stageros", "/clock", sub) for sub in
       ("/amcl", "/move_base", "/map_server", "/robot_state_publisher", "/rviz")),
    ("/stageros", "/scan", "/amcl"), ("/stageros", "/scan", "/move_base"), ("/stageros", "/scan", "/rviz"),
    ("/stageros", "/odom", "/move_base"),
    *(("/stageros", "/tf", sub) for sub in ("/amcl", "/move_base", "/rviz")),
    *((pub, "/tf", sub) for pub in ("/robot_state_publisher", "/amcl") for sub in ("/move_base", "/rviz")),
    ("/robot_state_publisher", "/tf", "/amcl"),
    *(("/robot_state_publisher", "/tf_static", sub) for sub in ("/amcl", "/move_base", "/rviz")),
    *(("/map_server", "/map", sub) for sub in ("/amcl", "/move_base", "/rviz")),
    ("/amcl", "/particlecloud", "/rviz"), ("/amcl", "/amcl_pose", "/rviz"),
    ("/move_base", "/mobile_base/commands/velocity", "/stageros"),
    *(("/move_base", topic, "/rviz") for topic in
       ("/move_base/NavfnROS/plan", "/move_base/DWAPlannerROS/local_plan", "/move_base/global_costmap/costmap",
        "/move_base/local_costmap/costmap")),
    ("/rviz", "/move_base_simple/goal", "/move_base"), ("/rviz", "/initialpose", "/amcl"),
]

COURSES = {"turtlesim and teleop": LESSON_ONE, "turtlesim and draw_square": DRAW_SQUARE,
           "turtle_tf2 demo": TURTLE_TF2, "TurtleBot navigation": NAVIGATION}


def course_snapshot(links: Links) -> GraphSnapshot:
    """What getSystemState and each node's getBusInfo answer for these connections."""
    publishers: dict[str, set[str]] = {}
    subscribers: dict[str, set[str]] = {}
    bus: dict[str, list[list[object]]] = {}
    for number, (publisher, topic, subscriber) in enumerate(links, 1):
        publishers.setdefault(topic, set()).add(publisher)
        subscribers.setdefault(topic, set()).add(subscriber)
        bus.setdefault(publisher, []).append([number, subscriber, "o", "TCPROS", topic, True])
        bus.setdefault(subscriber, [])
    state = [[[t, sorted(n)] for t, n in sorted(publishers.items())],
             [[t, sorted(n)] for t, n in sorted(subscribers.items())], []]
    uris = {node: f"http://127.0.0.1:{4000 + i}/" for i, node in enumerate(sorted(bus))}
    return snapshot_from(state, bus, uris)
