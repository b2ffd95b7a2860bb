"""rqt_console's model: a bounded store of log messages, the filters over it, and its file format (pure).

Rules:
- The store keeps the newest `capacity` messages (20,000 unless set); older ones fall out.
  Each message gets a sequence number when it arrives, so a view can tell what fell out.
- Messages come in batches (a subscriber hands over what arrived since the last update), and
  the view changes once per batch: at 10,000 messages a second the window redraws a few times
  a second, not 10,000 times.
- A message is shown when it passes the severity choice and matches none of the exclude rules;
  it is highlighted when it matches one of the highlight rules (with no highlight rules, none is).
  A rule tests one column (message, node, topics, location, or any) for a substring, or a
  regular expression; a bad expression matches nothing and says why.
- Pausing keeps what arrives (within the capacity) and shows it when the view resumes.
- Files are rqt_console's: `;`-separated, every field quoted, a header line naming the columns.
"""

from __future__ import annotations

import csv
import datetime
import io
import itertools
import re
from collections import deque
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass, field
from typing import NamedTuple

DEFAULT_CAPACITY = 20_000

DEBUG, INFO, WARN, ERROR, FATAL = 1, 2, 4, 8, 16
SEVERITY_NAMES = {DEBUG: "Debug", INFO: "Info", WARN: "Warn", ERROR: "Error", FATAL: "Fatal"}
SEVERITY_BY_NAME = {name.lower(): level for level, name in SEVERITY_NAMES.items()}
COLUMNS = ("message", "severity", "node", "stamp", "topics", "location")


class LogEntry(NamedTuple):
    """One rosgraph_msgs/Log as the console shows it. A NamedTuple: tens of thousands are kept."""

    message: str
    severity: int
    node: str
    secs: int
    nsecs: int
    topics: tuple[str, ...]
    file: str
    function: str
    line: int

    @property
    def severity_name(self) -> str:
        return SEVERITY_NAMES.get(self.severity, str(self.severity))

    @property
    def stamp(self) -> float:
        return self.secs + self.nsecs / 1e9

    @property
    def location(self) -> str:
        """rqt_console's location column: file:function:line."""
        return f"{self.file}:{self.function}:{self.line}"

    def column(self, name: str) -> str:
        if name == "severity":
            return self.severity_name
        if name == "stamp":
            return format_stamp(self.secs, self.nsecs)
        if name == "topics":
            return ", ".join(self.topics)
        if name == "location":
            return self.location
        if name == "message":
            return self.message
        if name == "node":
            return self.node
        raise KeyError(name)


def format_stamp(secs: int, nsecs: int) -> str:
    """As rqt_console shows a stamp: local wall-clock time with microseconds, and the date."""
    moment = datetime.datetime.fromtimestamp(secs + nsecs / 1e9)
    return moment.strftime("%H:%M:%S.%f (%Y-%m-%d)")


@dataclass(frozen=True)
class Rule:
    """A filter line: `text` searched in `column` ("any" for every column), as a regex if asked."""

    text: str
    column: str = "message"
    regex: bool = False

    def compiled(self) -> re.Pattern[str]:
        """Raises re.error for a bad regular expression."""
        return re.compile(self.text if self.regex else re.escape(self.text))


@dataclass(frozen=True)
class Filters:
    severities: frozenset[int] = frozenset(SEVERITY_NAMES)
    nodes: frozenset[str] = frozenset()  # empty: every node
    exclude: tuple[Rule, ...] = ()
    highlight: tuple[Rule, ...] = ()


class Matcher:
    """Filters made ready to test many messages; `errors` names the rules that did not compile."""

    def __init__(self, filters: Filters) -> None:
        self.filters = filters
        self.errors: list[str] = []
        self._exclude = self._compile(filters.exclude)
        self._highlight = self._compile(filters.highlight)

    def _compile(self, rules: Sequence[Rule]) -> list[tuple[str, re.Pattern[str]]]:
        out = []
        for rule in rules:
            if not rule.text:
                continue
            try:
                out.append((rule.column, rule.compiled()))
            except re.error as exc:
                self.errors.append(f"{rule.text!r}: {exc}")
        return out

    @staticmethod
    def _matches(entry: LogEntry, rules: list[tuple[str, re.Pattern[str]]]) -> bool:
        for column, pattern in rules:
            columns = COLUMNS if column == "any" else (column,)
            if any(pattern.search(entry.column(c)) for c in columns):
                return True
        return False

    def shows(self, entry: LogEntry) -> bool:
        if entry.severity not in self.filters.severities:
            return False
        if self.filters.nodes and entry.node not in self.filters.nodes:
            return False
        return not self._matches(entry, self._exclude)

    def highlights(self, entry: LogEntry) -> bool:
        return bool(self._highlight) and self._matches(entry, self._highlight)


@dataclass
class Change:
    """What one update did to the rows shown: `removed` from the top, `added` at the bottom;
    `reset` when everything was recomputed."""

    removed: int = 0
    added: int = 0
    reset: bool = False


@dataclass
class LogView:
    """The store and the rows it shows under the current filters."""

    capacity: int = DEFAULT_CAPACITY
    filters: Filters = field(default_factory=Filters)
    paused: bool = False

    def __post_init__(self) -> None:
        if self.capacity < 1:
            raise ValueError("the store must hold at least one message")
        self._store: deque[tuple[int, LogEntry]] = deque(maxlen=self.capacity)
        self._rows: deque[tuple[int, LogEntry]] = deque()
        self._next = 0
        self._shown_up_to = 0  # sequence number after the last stored message the rows were judged for
        self.matcher = Matcher(self.filters)
        self.received = 0

    def __len__(self) -> int:
        return len(self._rows)

    def row(self, index: int) -> LogEntry:
        return self._rows[index][1]

    def rows(self) -> Iterator[LogEntry]:
        return (entry for _, entry in self._rows)

    def stored(self) -> list[LogEntry]:
        return [entry for _, entry in self._store]

    @property
    def stored_count(self) -> int:
        return len(self._store)

    @property
    def first_kept(self) -> int:
        return self._store[0][0] if self._store else self._next

    def add(self, entries: Iterable[LogEntry]) -> Change:
        for entry in entries:
            self._store.append((self._next, entry))
            self._next += 1
            self.received += 1
        if self.paused:
            return Change()
        return self._catch_up()

    def _catch_up(self) -> Change:
        change = Change()
        first = self.first_kept
        while self._rows and self._rows[0][0] < first:
            self._rows.popleft()
            change.removed += 1
        unseen = self._next - max(self._shown_up_to, first)  # the store's newest, in O(unseen)
        for item in reversed(list(itertools.islice(reversed(self._store), unseen))):
            if self.matcher.shows(item[1]):
                self._rows.append(item)
                change.added += 1
        self._shown_up_to = self._next
        return change

    def set_paused(self, paused: bool) -> Change:
        self.paused = paused
        return Change() if paused else self._catch_up()

    def set_filters(self, filters: Filters) -> Change:
        self.filters = filters
        self.matcher = Matcher(filters)
        self._rows = deque(item for item in self._store if self.matcher.shows(item[1]))
        self._shown_up_to = self._next
        return Change(reset=True)

    def set_capacity(self, capacity: int) -> Change:
        if capacity < 1:
            raise ValueError("the store must hold at least one message")
        self.capacity = capacity
        self._store = deque(self._store, maxlen=capacity)
        return self.set_filters(self.filters)

    def clear(self) -> Change:
        self._store.clear()
        self._rows.clear()
        self._shown_up_to = self._next
        return Change(reset=True)

    def highlighted(self, index: int) -> bool:
        return self.matcher.highlights(self.row(index))

    def nodes(self) -> list[str]:
        return sorted({entry.node for _, entry in self._store})


def dump(entries: Iterable[LogEntry]) -> str:
    """The messages as rqt_console saves them."""
    out = io.StringIO()
    writer = csv.writer(out, delimiter=";", quoting=csv.QUOTE_ALL, lineterminator="\n")
    writer.writerow(COLUMNS)
    for entry in entries:
        writer.writerow([entry.message, entry.severity_name, entry.node, f"{entry.secs}.{entry.nsecs:09d}",
                         ", ".join(entry.topics), entry.location])
    return out.getvalue()


class FormatError(ValueError):
    """A file that is not a saved console log."""


def load(text: str) -> list[LogEntry]:
    rows = list(csv.reader(io.StringIO(text), delimiter=";"))
    if not rows or tuple(rows[0]) != COLUMNS:
        raise FormatError(f"not an rqt_console file: the first line must name the columns {';'.join(COLUMNS)}")
    entries = []
    for number, row in enumerate(rows[1:], start=2):
        if not row:
            continue
        if len(row) != len(COLUMNS):
            raise FormatError(f"line {number}: {len(row)} fields, expected {len(COLUMNS)}")
        message, severity, node, stamp, topics, location = row
        level = SEVERITY_BY_NAME.get(severity.lower())
        secs_text, _, nsecs_text = stamp.partition(".")
        file, function, line = location.rsplit(":", 2) if location.count(":") >= 2 else (location, "", "0")
        try:
            entry = LogEntry(message, level if level is not None else int(severity), node, int(secs_text),
                             int(nsecs_text.ljust(9, "0")[:9] or 0), tuple(t for t in topics.split(", ") if t),
                             file, function, int(line or 0))
        except ValueError as exc:
            raise FormatError(f"line {number}: {exc}") from None
        entries.append(entry)
    return entries
