"""interactive_markers.menu_handler: kame.interactive_markers.menu under its ROS name."""

from kame.interactive_markers.menu import CHECKED, NO_CHECKBOX, UNCHECKED, MenuHandler

__all__ = ["CHECKED", "NO_CHECKBOX", "UNCHECKED", "MenuHandler"]
