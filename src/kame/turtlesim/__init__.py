"""turtlesim, as kame builds it: a pure world model (`world`, `canvas`), the ROS node that
steps it and publishes it (`node`), an optional Qt window that draws it (`gui`), and the
package's other programs (`teleop_key`, `draw_square`, `mimic`).

Rule (docs/ARCHITECTURE.md, 4): the world knows nothing of ROS; the GUI knows only the
world; the node glues. This package's public API is the world's.
"""

from kame.turtlesim.canvas import Canvas, Rgb
from kame.turtlesim.world import (
    COMMAND_TIMEOUT,
    DEFAULT_BACKGROUND,
    DEFAULT_PEN_COLOR,
    DEFAULT_PEN_WIDTH,
    PIXELS_PER_METRE,
    UPDATE_PERIOD,
    WINDOW_PIXELS,
    InvalidValue,
    NameTaken,
    NoSuchTurtle,
    Pen,
    Pose,
    Segment,
    Snapshot,
    Sprite,
    StepReport,
    TurtleError,
    TurtleUpdate,
    TurtleView,
    WallHit,
    World,
    wrap_angle,
)

__all__ = [
    "COMMAND_TIMEOUT", "DEFAULT_BACKGROUND", "DEFAULT_PEN_COLOR", "DEFAULT_PEN_WIDTH", "PIXELS_PER_METRE",
    "UPDATE_PERIOD", "WINDOW_PIXELS", "Canvas", "InvalidValue", "NameTaken", "NoSuchTurtle", "Pen", "Pose",
    "Rgb", "Segment", "Snapshot", "Sprite", "StepReport", "TurtleError", "TurtleUpdate",
    "TurtleView", "WallHit", "World", "wrap_angle",
]
