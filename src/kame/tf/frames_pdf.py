"""frames.pdf without graphviz: the frame tree drawn top-down as a one-page PDF.

Each frame is an ellipse with its name; each parent -> child edge is an arrow labelled with
the lines view_frames shows (broadcaster, rate, ...); a legend box says when it was recorded.
Pure: edges in, PDF bytes out. Layout is a tidy tree: leaves side by side in depth-first
order, each parent centred over its children, one row per depth, a column as wide as its
frame's name and label. An edge's label is a block on a white ground over the arrow, halfway
down, centred on the child's column (so the labels of siblings stand side by side); a block
that would still meet another moves right until it is clear (graphviz lets the labels of two
edges from one parent overlap: the tf tutorial's world -> turtle1 and world -> turtle2 did).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import NamedTuple


class Edge(NamedTuple):
    parent: str
    child: str
    label: tuple[str, ...]


FONT = 10.0
LABEL_FONT = 7.0
ROW = 120.0
MARGIN = 40.0
NODE_HEIGHT = 28.0
LABEL_LINE = LABEL_FONT * 1.2
LABEL_GAP = 6.0  # between two label blocks moved apart


class Box(NamedTuple):
    """A label block: left, top (downwards from the first row's centre), width, height."""
    x: float
    y: float
    w: float
    h: float

    def meets(self, other: Box) -> bool:
        return (self.x < other.x + other.w and other.x < self.x + self.w and self.y < other.y + other.h
                and other.y < self.y + self.h)


def _text_width(text: str, size: float) -> float:
    return 0.52 * size * len(text)  # Helvetica's average advance, near enough for layout


def _column_width(name: str, labels: Sequence[str]) -> float:
    widest = max([_text_width(name, FONT) + 30.0, *(_text_width(line, LABEL_FONT) for line in labels)])
    return widest + 30.0


def _escape(text: str) -> str:
    safe = text.encode("latin-1", "replace").decode("latin-1")
    return safe.replace("\\", "\\\\").replace("(", "\\(").replace(")", "\\)")


def _layout(edges: Sequence[Edge]) -> tuple[dict[str, tuple[float, int]], float, int]:
    """(x centre, depth) of each frame, the page's content width and the deepest row."""
    children: dict[str, list[str]] = {}
    parents: dict[str, str] = {}
    labels: dict[str, tuple[str, ...]] = {}
    order: list[str] = []
    for edge in edges:
        for name in (edge.parent, edge.child):
            if name not in children:
                children[name] = []
                order.append(name)
        if edge.child not in parents:
            children[edge.parent].append(edge.child)
            parents[edge.child] = edge.parent
            labels[edge.child] = edge.label
    roots = [name for name in order if name not in parents]
    placed: dict[str, tuple[float, int]] = {}
    cursor = 0.0
    deepest = 0

    def place(name: str, depth: int) -> float:
        nonlocal cursor, deepest
        deepest = max(deepest, depth)
        kids = [kid for kid in children[name] if kid not in placed]
        placed[name] = (0.0, depth)  # marks it, so a loop in the input cannot recurse forever
        start, before = cursor, set(placed)
        width = _column_width(name, labels.get(name, ()))
        if not kids:
            x = cursor + width / 2
            cursor += width
        else:
            xs = [place(kid, depth + 1) for kid in kids]
            x = (xs[0] + xs[-1]) / 2  # centred over its children
            if cursor - start < width:  # itself wider than its subtree: the subtree moves to its middle
                shift = (width - (cursor - start)) / 2
                for below in set(placed) - before:
                    placed[below] = (placed[below][0] + shift, placed[below][1])
                x += shift
                cursor = start + width
        placed[name] = (x, depth)
        return x

    for root in roots or order[:1]:
        place(root, 0)
    for name in order:  # frames only on a loop, unreachable from any root
        if name not in placed:
            place(name, 0)
    return placed, cursor, deepest


def _ends(edge: Edge, positions: dict[str, tuple[float, int]]) -> tuple[tuple[float, float], tuple[float, float]]:
    """An arrow's ends, (x, y downwards from the first row's centre): parent's bottom, child's top."""
    (px, pdepth), (cx, cdepth) = positions[edge.parent], positions[edge.child]
    return (px, pdepth * ROW + NODE_HEIGHT / 2), (cx, cdepth * ROW - NODE_HEIGHT / 2)


def label_boxes(edges: Sequence[Edge]) -> dict[int, Box]:
    """Each labelled edge's label block (by the edge's index), no two meeting: halfway down its
    arrow, centred on its child's column, or moved right of the blocks it would meet."""
    positions = _layout(edges)[0]
    placed: dict[int, Box] = {}
    wanted = []
    for index, edge in enumerate(edges):
        if edge.label and edge.parent in positions and edge.child in positions:
            (_, y1), (x2, y2) = _ends(edge, positions)
            w = max(_text_width(line, LABEL_FONT) for line in edge.label) + 4.0
            h = len(edge.label) * LABEL_LINE + 2.0
            wanted.append((index, Box(x2 - w / 2, (y1 + y2) / 2 - h / 2, w, h)))
    for index, box in sorted(wanted, key=lambda item: (item[1].y, item[1].x)):
        while True:
            blocking = [other for other in placed.values() if box.meets(other)]
            if not blocking:
                break
            box = box._replace(x=max(other.x + other.w for other in blocking) + LABEL_GAP)
        placed[index] = box
    return placed


def render(edges: Sequence[Edge], legend: Sequence[str]) -> bytes:
    """A PDF page of the tree; `legend` lines go in a box at the top."""
    positions, content_width, deepest = _layout(edges)
    labels = label_boxes(edges)
    content_width = max([content_width, *(box.x + box.w for box in labels.values())])
    legend_width = max([_text_width(line, FONT) for line in legend] + [0.0]) + 20.0
    width = max(content_width, legend_width, 200.0) + 2 * MARGIN
    legend_height = (len(legend) + 1) * FONT * 1.4 if legend else 0.0
    height = (deepest + 1) * ROW + legend_height + 2 * MARGIN
    ops: list[str] = ["0.6 w"]

    def y_of(depth: int) -> float:
        return height - MARGIN - legend_height - NODE_HEIGHT / 2 - depth * ROW - 10.0

    def text(x: float, y: float, line: str, size: float) -> None:
        ops.append(f"BT /F1 {size:g} Tf {x:.2f} {y:.2f} Td ({_escape(line)}) Tj ET")

    if legend:
        top = height - MARGIN
        ops.append(f"{MARGIN:.2f} {top - legend_height:.2f} {legend_width:.2f} {legend_height:.2f} re S")
        for index, line in enumerate(legend):
            text(MARGIN + 10.0, top - (index + 1) * FONT * 1.4, line, FONT)
    for name, (x, depth) in positions.items():
        cx, cy = x + MARGIN, y_of(depth)
        rx, ry = _text_width(name, FONT) / 2 + 14.0, NODE_HEIGHT / 2
        k = 0.5523  # Bezier circle constant
        ops.append(f"{cx + rx:.2f} {cy:.2f} m "
                   f"{cx + rx:.2f} {cy + k * ry:.2f} {cx + k * rx:.2f} {cy + ry:.2f} {cx:.2f} {cy + ry:.2f} c "
                   f"{cx - k * rx:.2f} {cy + ry:.2f} {cx - rx:.2f} {cy + k * ry:.2f} {cx - rx:.2f} {cy:.2f} c "
                   f"{cx - rx:.2f} {cy - k * ry:.2f} {cx - k * rx:.2f} {cy - ry:.2f} {cx:.2f} {cy - ry:.2f} c "
                   f"{cx + k * rx:.2f} {cy - ry:.2f} {cx + rx:.2f} {cy - k * ry:.2f} {cx + rx:.2f} {cy:.2f} c S")
        text(cx - _text_width(name, FONT) / 2, cy - FONT / 3, name, FONT)
    for edge in edges:
        if edge.parent not in positions or edge.child not in positions:
            continue
        (x1, y1), (x2, y2) = ((x + MARGIN, y_of(0) - y) for x, y in _ends(edge, positions))
        ops.append(f"{x1:.2f} {y1:.2f} m {x2:.2f} {y2:.2f} l S")
        ops.append(f"{x2:.2f} {y2:.2f} m {x2 - 3:.2f} {y2 + 7:.2f} l {x2 + 3:.2f} {y2 + 7:.2f} l h f")
    for index, box in labels.items():  # over the arrows, each on its white ground
        left, top = box.x + MARGIN, y_of(0) - box.y
        ops.append(f"1 g {left:.2f} {top - box.h:.2f} {box.w:.2f} {box.h:.2f} re f 0 g")
        for row, line in enumerate(edges[index].label):
            text(left + 2.0, top - 1.0 - (row + 1) * LABEL_LINE + LABEL_FONT * 0.2, line, LABEL_FONT)
    return _pdf("\n".join(ops).encode("latin-1"), width, height)


def _pdf(content: bytes, width: float, height: float) -> bytes:
    objects = [
        b"<< /Type /Catalog /Pages 2 0 R >>",
        b"<< /Type /Pages /Kids [3 0 R] /Count 1 >>",
        (f"<< /Type /Page /Parent 2 0 R /MediaBox [0 0 {width:.0f} {height:.0f}] /Contents 4 0 R "
         f"/Resources << /Font << /F1 5 0 R >> >> >>").encode(),
        b"<< /Length %d >>\nstream\n" % len(content) + content + b"\nendstream",
        b"<< /Type /Font /Subtype /Type1 /BaseFont /Helvetica /Encoding /WinAnsiEncoding >>",
    ]
    out = bytearray(b"%PDF-1.4\n")
    offsets = []
    for number, body in enumerate(objects, start=1):
        offsets.append(len(out))
        out += b"%d 0 obj\n" % number + body + b"\nendobj\n"
    xref = len(out)
    out += b"xref\n0 %d\n0000000000 65535 f \n" % (len(objects) + 1)
    for offset in offsets:
        out += b"%010d 00000 n \n" % offset
    out += b"trailer\n<< /Size %d /Root 1 0 R >>\nstartxref\n%d\n%%%%EOF\n" % (len(objects) + 1, xref)
    return bytes(out)
