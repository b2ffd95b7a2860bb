"""The rqt tools: rqt_graph, rqt_plot, rqt_console and rqt_logger_level.

Each tool is a pure model (graph_model with graph_layout and graph_export, plot_model,
console_model: no Qt, no sockets), a source that talks to ROS through kame.node
(graph_source, plot_source, console_source, logger_source), a Qt window that only draws the
model (*_window), and its command (*_main, installed as rqt_graph, rqt_plot, rqt_console,
rqt_logger_level and shipped as ROS packages for rosrun).
"""
