"""roslib, for the old tutorials' first lines (`import roslib; roslib.load_manifest('pkg')`)."""


def load_manifest(package_name: str) -> None:
    """A no-op, as in catkin-era ROS: packages and their messages are found on import."""
