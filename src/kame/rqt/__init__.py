"""The rqt tools and the rqt window that docks them as plugins.

Each tool is a pure model (graph_model with graph_layout and graph_export, plot_model,
console_model, message_tree, topic_model, image_model: no Qt, no sockets), a source that talks
to ROS through kame.node (graph_source, plot_source, console_source, logger_source,
topic_source, publisher_source, service_source, image_source), a Qt window that only draws the
model (*_window), and its command (*_main, or gui_main's standalone entry points), installed
and shipped as ROS packages for rosrun. The rqt window (gui_window) opens the tools as dock
widgets through `plugins`, and keeps its layout as a `perspective`.
"""
