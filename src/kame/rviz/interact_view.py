"""The Interact tool in rviz's window: the view's mouse events on an interactive marker's
control go to kame.rviz.interact (which drags and makes the feedback), the feedback is
published on the display's <ns>/feedback, and a marker's menu shows as a context menu whose
choice is sent back as MENU_SELECT; the control under the mouse is brightened as rviz's is
(more while pressed). Everything else about the tool is Qt-free."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from PySide6.QtCore import QPoint
from PySide6.QtWidgets import QMenu

from kame.rviz.interact import Interaction, menu_tree, mouse_ray, pick, pointer
from kame.rviz.interactive import Handle, InteractiveMarkers

HOVER, ACTIVE = 0.3, 0.5  # rviz's highlights: a control under the mouse, one pressed


class InteractRouter:
    def __init__(self, view: Any, displays: Callable[[], list[Any]], publish: Callable[[str, Any], None] | None,
                 node_name: str, redraw: Callable[[], None]) -> None:
        self.view = view
        self.displays = displays
        self.publish = publish
        self.redraw = redraw
        self.interaction = Interaction(node_name)
        self.menu: QMenu | None = None  # the marker's menu open now: a window of its own, kept alive here

    def _markers(self) -> list[InteractiveMarkers]:
        return [d for d in self.displays() if isinstance(d, InteractiveMarkers) and d.enabled]

    def _send(self, handle: Handle, feedback: list[Any]) -> None:
        if self.publish is not None:
            for message in feedback:
                self.publish(handle.feedback_topic, message)

    def __call__(self, kind: str, x: float, y: float, right: bool, shift: bool = False, control: bool = False,
                 wheel: float = 0.0) -> bool:
        """A mouse event at pixel (x, y) of the view ("hover", "press", "move", "wheel": turned by
        `wheel`, "release"), Shift and Ctrl held or not; whether the tool took it (False: nothing
        interactive was pressed, the camera moves)."""
        size = self.view.width(), self.view.height()
        origin, direction = mouse_ray(self.view.camera, x, y, *size)
        at = pointer(self.view.camera, x, y, *size, shift, control)
        drag = self.interaction.drag
        if kind == "hover":  # no button down: rviz brightens the control under the mouse
            found = pick([h for d in self._markers() for h in d.handles], origin, direction)
            self._highlight(found[0] if found else None, HOVER)
            return False
        if kind == "press":
            pressed = self.interaction.press([h for d in self._markers() for h in d.handles], origin, direction, right,
                                             at)
            if self.interaction.drag is not None:
                self._send(self.interaction.drag.handle, pressed.feedback)
                self._highlight(self.interaction.drag.handle, ACTIVE)
            return pressed.consumed
        if kind == "release":
            sent = self.interaction.release()
            if drag is not None:
                self._send(drag.handle, sent)
                self._highlight(drag.handle, HOVER)
            if self.interaction.menu is not None:  # rviz opens a menu on the release
                self._menu(self.interaction.menu, QPoint(round(x), round(y)))
            return drag is not None or self.interaction.menu is not None
        if drag is None:
            return False
        sent = self.interaction.wheel(wheel) if kind == "wheel" else self.interaction.move(origin, direction, at)
        self._send(drag.handle, sent)
        if sent:
            for display in self._markers():
                display.moved()
            self.redraw()
        return True

    def _highlight(self, handle: Handle | None, amount: float) -> None:
        changed = False
        for display in self._markers():
            before = display.version
            mine = handle is not None and (handle.display_name, handle.feedback_topic) == (
                display.name, display.feedback_topic())
            display.highlight(handle if mine else None, amount)
            changed = changed or display.version != before
        if changed:
            self.redraw()

    def _menu(self, handle: Handle, at: QPoint) -> None:
        tree = menu_tree(list(handle.marker.menu_entries))
        menu = self.menu = QMenu()  # the view is a window, not a widget: no parent to own the menu

        def fill(parent: QMenu, parent_id: int) -> None:
            for entry in tree.get(parent_id, []):
                if entry.id in tree:
                    fill(parent.addMenu(entry.title), entry.id)
                else:
                    action = parent.addAction(entry.title)
                    action.triggered.connect(lambda _checked=False, entry_id=entry.id: self._send(
                        handle, [self.interaction.menu_select(handle, entry_id)]))

        fill(menu, 0)
        menu.popup(self.view.mapToGlobal(at))
