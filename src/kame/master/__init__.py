"""The ROS master: registrations, parameter server and the XML-RPC API (pure core), and the server.

`MasterApi` is the pure core (no I/O: changes come back as `Notification` values); `server`
puts it on the network.
"""

from kame.master.api import CallResult, MasterApi
from kame.master.notifications import Notification, ParamUpdate, PublisherUpdate, ShutdownNode

__all__ = ["CallResult", "MasterApi", "Notification", "ParamUpdate", "PublisherUpdate", "ShutdownNode"]
