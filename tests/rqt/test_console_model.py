"""rqt_console's model without a window: the bounded store, batches, filters, pause, files."""

from __future__ import annotations

import pytest

from kame.rqt.console_model import (
    DEBUG,
    ERROR,
    INFO,
    WARN,
    Change,
    Filters,
    FormatError,
    LogEntry,
    LogView,
    Rule,
    dump,
    load,
)


def entry(n: int, message: str = "", severity: int = INFO, node: str = "/talker") -> LogEntry:
    return LogEntry(message or f"hello {n}", severity, node, 1700000000 + n, 5000, ("/chatter", "/rosout"),
                    f"/ws{node}.py", "talk", 20 + n)


def test_the_store_is_bounded_and_the_rows_follow_it() -> None:
    view = LogView(capacity=5)
    assert view.add([entry(i) for i in range(3)]) == Change(added=3)
    change = view.add([entry(i) for i in range(3, 7)])
    assert change == Change(removed=2, added=4)  # two fell out of the store
    assert [e.message for e in view.rows()] == [f"hello {i}" for i in range(2, 7)]
    assert view.received == 7 and len(view.stored()) == 5
    # a batch bigger than the store keeps its newest
    assert view.add([entry(i) for i in range(100, 112)]) == Change(removed=5, added=5)
    assert view.row(0).message == "hello 107"
    with pytest.raises(ValueError):
        LogView(capacity=0)


def test_severity_node_and_text_filters() -> None:
    view = LogView()
    view.add([entry(0, "Oh no! I hit the wall!", WARN, "/turtlesim"), entry(1, "Spawning turtle", INFO, "/turtlesim"),
              entry(2, "tick", DEBUG, "/talker"), entry(3, "cannot open", ERROR, "/talker")])
    view.set_filters(Filters(severities=frozenset({WARN, ERROR})))
    assert [e.message for e in view.rows()] == ["Oh no! I hit the wall!", "cannot open"]
    view.set_filters(Filters(nodes=frozenset({"/turtlesim"})))
    assert len(view) == 2
    view.set_filters(Filters(exclude=(Rule("wall"),)))
    assert "Oh no! I hit the wall!" not in [e.message for e in view.rows()]
    view.set_filters(Filters(exclude=(Rule(r"^(tick|Spawn)", regex=True),)))
    assert [e.message for e in view.rows()] == ["Oh no! I hit the wall!", "cannot open"]
    view.set_filters(Filters(exclude=(Rule("talker.py", column="location"),)))
    assert len(view) == 2
    view.set_filters(Filters(highlight=(Rule("WALL|open", column="any", regex=True),)))
    assert [view.highlighted(i) for i in range(len(view))] == [False, False, False, True]
    view.set_filters(Filters(highlight=(Rule("(wall", regex=True),)))
    assert view.matcher.errors and len(view) == 4 and not view.highlighted(0)  # a bad regex matches nothing
    # messages that arrive later are judged by the filters in force
    view.set_filters(Filters(severities=frozenset({WARN})))
    assert view.add([entry(9, "again", WARN), entry(10, "quiet", INFO)]) == Change(added=1)


def test_pause_keeps_messages_for_later_and_clear_empties() -> None:
    view = LogView(capacity=10)
    view.add([entry(0)])
    view.set_paused(True)
    assert view.add([entry(i) for i in range(1, 5)]) == Change()
    assert len(view) == 1
    assert view.set_paused(False) == Change(added=4)
    assert len(view) == 5
    assert view.clear().reset and len(view) == 0 and view.stored() == []
    assert view.add([entry(7)]) == Change(added=1)
    assert view.set_capacity(3).reset and view.capacity == 3


def test_save_and_load_round_trip() -> None:
    entries = [entry(0, 'quotes " and ; semicolons', WARN), entry(1, "line\nbreak", ERROR, "/other")]
    text = dump(entries)
    assert text.splitlines()[0] == '"message";"severity";"node";"stamp";"topics";"location"'
    assert '"Warn";"/talker";"1700000000.000005000";"/chatter, /rosout";"/ws/talker.py:talk:20"' in text
    assert load(text) == entries
    with pytest.raises(FormatError):
        load("not;a;console;file\n")
    with pytest.raises(FormatError, match="line 2"):
        load('"message";"severity";"node";"stamp";"topics";"location"\n"a";"Info"\n')


def test_stamps_and_columns_read_as_rqt_console_shows_them() -> None:
    e = entry(0)
    assert e.column("severity") == "Info" and e.column("topics") == "/chatter, /rosout"
    assert e.column("location") == "/ws/talker.py:talk:20"
    assert e.column("stamp").split(" ")[0].endswith(".000005")  # local time of day, microseconds
    assert e.column("stamp").split(" ")[1] in ("(2023-11-14)", "(2023-11-15)")  # the date in any time zone
