"""interactive_markers' MenuHandler (ROS 1, 1.12), without I/O: a tree of entries, each with a
title, a check state and a callback; apply() writes the visible entries into a marker of a
server as MenuEntry messages (ids from 1, parent 0 for the top level, "[x] "/"[ ] " before a
checked/unchecked title) and routes the marker's MENU_SELECT feedback to the entry's callback."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from visualization_msgs.msg import InteractiveMarkerFeedback, MenuEntry

NO_CHECKBOX, CHECKED, UNCHECKED = 0, 1, 2
CHECK_PREFIX = {NO_CHECKBOX: "", CHECKED: "[x] ", UNCHECKED: "[ ] "}


@dataclass
class Entry:
    title: str
    command: str
    command_type: int
    callback: Callable[[Any], None] | None
    sub_entries: list[int] = field(default_factory=list)
    visible: bool = True
    check_state: int = NO_CHECKBOX


class MenuHandler:
    NO_CHECKBOX, CHECKED, UNCHECKED = NO_CHECKBOX, CHECKED, UNCHECKED

    def __init__(self) -> None:
        self.top_level: list[int] = []
        self.entries: dict[int, Entry] = {}
        self.managed_markers: set[str] = set()

    def insert(self, title: str, parent: int | None = None, command_type: int = MenuEntry.FEEDBACK,
               command: str = "", callback: Callable[[Any], None] | None = None) -> int | None:
        """A new entry's handle (None: `parent` is no entry)."""
        if parent is not None and parent not in self.entries:
            return None
        handle = len(self.entries) + 1
        self.entries[handle] = Entry(title, command, command_type, callback)
        (self.entries[parent].sub_entries if parent is not None else self.top_level).append(handle)
        return handle

    def setVisible(self, handle: int, visible: bool) -> bool:
        entry = self.entries.get(handle)
        if entry is not None:
            entry.visible = visible
        return entry is not None

    def setCheckState(self, handle: int, check_state: int) -> bool:
        entry = self.entries.get(handle)
        if entry is not None:
            entry.check_state = check_state
        return entry is not None

    def getCheckState(self, handle: int) -> int | None:
        entry = self.entries.get(handle)
        return entry.check_state if entry is not None else None

    def getTitle(self, handle: int) -> str | None:
        entry = self.entries.get(handle)
        return entry.title if entry is not None else None

    def menu_entries(self) -> list[Any]:
        """The visible entries as MenuEntry messages, each parent before its children."""
        entries: list[Any] = []
        self._push(self.top_level, 0, entries)
        return entries

    def _push(self, handles: list[int], parent: int, out: list[Any]) -> None:
        for handle in handles:
            entry = self.entries[handle]
            if not entry.visible:
                continue
            title = CHECK_PREFIX.get(entry.check_state, "") + entry.title
            out.append(MenuEntry(id=handle, parent_id=parent, title=title, command=entry.command,
                                 command_type=entry.command_type))
            self._push(entry.sub_entries, handle, out)

    def apply(self, server: Any, marker_name: str) -> bool:
        """Writes the menu into `server`'s marker `marker_name` (at its next applyChanges) and
        takes its MENU_SELECT feedback."""
        marker = server.get(marker_name)
        if not marker:
            self.managed_markers.discard(marker_name)
            return False
        marker.menu_entries = self.menu_entries()
        server.insert(marker, self.processFeedback, InteractiveMarkerFeedback.MENU_SELECT)
        self.managed_markers.add(marker_name)
        return True

    def reApply(self, server: Any) -> bool:
        results = [self.apply(server, name) for name in sorted(self.managed_markers)]
        return all(results)

    def processFeedback(self, feedback: Any) -> None:
        entry = self.entries.get(feedback.menu_entry_id)
        if entry is not None and entry.callback is not None:
            entry.callback(feedback)
