"""Where rqt_graph draws each node, topic, edge and namespace box (pure; no graphviz binary).

Rules: a layered (Sugiyama) layout from grandalf, turned to run left to right as rqt_graph's
`rankdir=LR`: publishers left of their topics, subscribers right. A namespace's members are
laid out as one vertex, stacked in its frame (graphviz lays a cluster out whole): one frame a
namespace, holding nothing else. Each connected part of the graph is laid out on its own and
the parts are stacked top to bottom; the drawing is moved so that nothing, curves included,
lies above or left of its margin. Edges are polylines
through grandalf's dummy vertices, clipped to the shapes' borders; a node's edge to itself
is a loop above it, and parallel edges between the same two vertices (either way round) bow
apart, a label's height and more from each other. Each edge label gets a box of its own,
placed along its edge where it meets no other label and no vertex (nodes-only mode labels an
edge with its topic: graphviz prints two topics between one pair of nodes over each other). Text is
measured by the caller (the window passes its font's metrics); `text_width` estimates it
for drawings made without Qt (the SVG of `rqt_graph --output`).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

from grandalf.graphs import Edge, Graph, Vertex
from grandalf.layouts import SugiyamaLayout

from kame.rqt.graph_model import Kind, Scene

FONT_SIZE = 12.0
MARGIN = 16.0
NODE_PAD = (28.0, 20.0)  # ellipse: room left and right of the text, above and below
TOPIC_PAD = (16.0, 14.0)
VERTEX_GAP = 18.0  # between vertices of one layer; room for cluster frames and titles when grouping
LAYER_GAP = 56.0  # between layers; nodes-only mode adds the widest edge label
PART_GAP = 28.0  # between the laid-out connected parts
GROUP_PAD = 10.0
GROUP_TITLE = 16.0
STACK_GAP = 12.0  # between the members of a namespace's frame
GROUP_PREFIX = "g:"  # a namespace's frame as one vertex of the layering
LOOP = 26.0
LABEL_HEIGHT = FONT_SIZE + 4.0
LABEL_LIFT = 6.0  # a label's bottom sits this far above its point on the edge
TWIN_GAP = LABEL_HEIGHT + LABEL_LIFT + 10.0  # between parallel edges: room for a label between them
LABEL_ALONG = (0.5, 0.4, 0.6, 0.3, 0.7, 0.2, 0.8)  # where along its edge a label may sit, first choice first

Point = tuple[float, float]
Measure = Callable[[str], float]


@dataclass(frozen=True)
class Box:
    x: float  # top left
    y: float
    w: float
    h: float

    @property
    def centre(self) -> Point:
        return (self.x + self.w / 2, self.y + self.h / 2)

    def united(self, other: Box) -> Box:
        x, y = min(self.x, other.x), min(self.y, other.y)
        return Box(x, y, max(self.x + self.w, other.x + other.w) - x, max(self.y + self.h, other.y + other.h) - y)


@dataclass(frozen=True)
class Layout:
    scene: Scene
    boxes: dict[str, Box]  # vertex id -> its shape's bounding box
    paths: tuple[tuple[Point, ...], ...]  # one per scene edge, source to target
    labels: dict[int, Box]  # edge index -> its label's box (edges with a label only)
    groups: dict[str, Box]  # namespace -> its frame, holding its members and nothing else
    width: float
    height: float



def text_width(text: str, size: float = FONT_SIZE) -> float:
    """An estimate of `text`'s width in a sans-serif font of `size` px."""
    em = 0.0
    for char in text:
        if char in "il.,:;'|!/[]()-tfrj ":
            em += 0.32
        elif char in "mwMW@":
            em += 0.86
        elif char.isupper() or char in "_#%&":
            em += 0.68
        else:
            em += 0.56
    return em * size


def vertex_size(kind: Kind, label: str, measure: Measure) -> tuple[float, float]:
    pad = NODE_PAD if kind is Kind.NODE else TOPIC_PAD
    return (measure(label) + 2 * pad[0], FONT_SIZE + 2 * pad[1])


class _View:
    """grandalf's view of a vertex, sized as turned a quarter: its w is our height."""

    def __init__(self, w: float, h: float) -> None:
        self.w = w
        self.h = h
        self.xy: Point = (0.0, 0.0)


class _EdgeView:
    def __init__(self) -> None:
        self.points: list[Point] = []

    def setpath(self, points: list[Point]) -> None:
        self.points = list(points)


def layout(scene: Scene, measure: Measure = text_width) -> Layout:
    sizes = {v.id: vertex_size(v.kind, v.name, measure) for v in scene.vertices}
    layer_gap = LAYER_GAP + max((measure(e.label) for e in scene.edges if e.label), default=0.0)
    # a namespace's members are one vertex of the layering (as graphviz lays a cluster out
    # whole), stacked top to bottom inside its frame: one frame per namespace, holding no other
    placed_as = {v.id: v.id for v in scene.vertices}
    stacks: dict[str, tuple[str, ...]] = {}
    for group in scene.groups:
        stacks[GROUP_PREFIX + group.namespace] = tuple(sorted(group.members))
        placed_as.update((member, GROUP_PREFIX + group.namespace) for member in group.members)
    layered = {vid: size for vid, size in sizes.items() if placed_as[vid] == vid}
    layered.update((gid, _stack_size([sizes[m] for m in members])) for gid, members in stacks.items())
    vertices = {vid: Vertex(vid) for vid in layered}
    for vid, vertex in vertices.items():
        vertex.view = _View(layered[vid][1], layered[vid][0])
    pairs: dict[tuple[str, str], Edge] = {}
    for edge in scene.edges:
        key = (placed_as[edge.source], placed_as[edge.target])
        if key[0] != key[1] and key not in pairs and (key[1], key[0]) not in pairs:
            pairs[key] = Edge(vertices[key[0]], vertices[key[1]])
            pairs[key].view = _EdgeView()
    graph = Graph(list(vertices.values()), list(pairs.values()))
    centres: dict[str, Point] = {}
    routes: dict[tuple[str, str], list[Point]] = {}
    top = MARGIN
    for part in sorted(graph.C, key=lambda c: min(str(v.data) for v in c.sV)):
        placed = _place_part(part, layer_gap, VERTEX_GAP)
        ys = [y - layered[vid][1] / 2 for vid, (_, y) in placed.items()]
        xs = [x - layered[vid][0] / 2 for vid, (x, _) in placed.items()]
        dx, dy = MARGIN - min(xs), top - min(ys)
        for vid, (x, y) in placed.items():
            centres[vid] = (x + dx, y + dy)
        for e in part.sE:
            routes[(e.v[0].data, e.v[1].data)] = [(x + dx, y + dy) for x, y in _turn(e.view.points)]
        top = max(centres[vid][1] + layered[vid][1] / 2 for vid in placed) + PART_GAP
    frames = {gid: Box(centres[gid][0] - layered[gid][0] / 2, centres[gid][1] - layered[gid][1] / 2, *layered[gid])
              for gid in stacks}
    for gid, members in stacks.items():
        centres.update(_stacked(frames[gid], [(m, sizes[m]) for m in members]))
    boxes = {vid: Box(centres[vid][0] - w / 2, centres[vid][1] - h / 2, w, h) for vid, (w, h) in sizes.items()}
    kinds = {v.id: v.kind for v in scene.vertices}
    paths = tuple(_edge_path(scene, index, boxes, kinds, routes, placed_as) for index in range(len(scene.edges)))
    groups = {group.namespace: frames[GROUP_PREFIX + group.namespace] for group in scene.groups}
    labels = _place_labels(scene, paths, boxes, measure)
    extent = list(boxes.values()) + list(groups.values()) + list(labels.values())
    # the curves drawn through the paths stay inside their Bezier control points
    drawn = [point for path in paths for point in path] + [
        point for path in paths for segment in cubic_segments(path) for point in segment]
    xs = [b.x for b in extent] + [b.x + b.w for b in extent] + [x for x, _ in drawn]
    ys = [b.y for b in extent] + [b.y + b.h for b in extent] + [y for _, y in drawn]
    if not xs:
        return Layout(scene, {}, (), {}, {}, 2 * MARGIN, 2 * MARGIN)
    # group titles, labels and curves above or left of the parts: everything moves in
    dx, dy = max(0.0, MARGIN - min(xs)), max(0.0, MARGIN - min(ys))
    if dx or dy:
        boxes = {k: Box(b.x + dx, b.y + dy, b.w, b.h) for k, b in boxes.items()}
        groups = {k: Box(b.x + dx, b.y + dy, b.w, b.h) for k, b in groups.items()}
        paths = tuple(tuple((x + dx, y + dy) for x, y in path) for path in paths)
        labels = {k: Box(b.x + dx, b.y + dy, b.w, b.h) for k, b in labels.items()}
    return Layout(scene, boxes, paths, labels, groups, max(xs) + dx + MARGIN, max(ys) + dy + MARGIN)


def _place_labels(scene: Scene, paths: Sequence[Sequence[Point]], boxes: dict[str, Box],
                  measure: Measure) -> dict[int, Box]:
    """A box for each edge's label, above a point of its edge: the first of LABEL_ALONG that
    meets no label placed before and no vertex, else the middle, moved down until it is free."""
    placed: dict[int, Box] = {}
    taken = list(boxes.values())
    for index, edge in enumerate(scene.edges):
        if not edge.label:
            continue
        width = measure(edge.label) + 4.0
        candidates = [_label_box(_along(paths[index], t), width) for t in LABEL_ALONG]
        box = next((c for c in candidates if not any(_overlaps(c, other) for other in taken)), None)
        if box is None:
            box = candidates[0]
            while any(_overlaps(box, other) for other in taken):
                box = Box(box.x, box.y + LABEL_HEIGHT, box.w, box.h)
        placed[index] = box
        taken.append(box)
    return placed


def _label_box(point: Point, width: float) -> Box:
    return Box(point[0] - width / 2, point[1] - LABEL_LIFT - LABEL_HEIGHT, width, LABEL_HEIGHT)


def _along(points: Sequence[Point], t: float) -> Point:
    """The point a fraction `t` of the way along a polyline, by length."""
    lengths = [math.dist(a, b) for a, b in itertools.pairwise(points)]
    goal = sum(lengths) * t
    for (a, b), length in zip(itertools.pairwise(points), lengths, strict=True):
        if goal <= length and length > 0:
            f = goal / length
            return (a[0] + (b[0] - a[0]) * f, a[1] + (b[1] - a[1]) * f)
        goal -= length
    return points[-1]


def _stack_size(sizes: Sequence[tuple[float, float]]) -> tuple[float, float]:
    """A namespace's frame: its members one above the other, the title on top."""
    width = max(w for w, _ in sizes) + 2 * GROUP_PAD
    height = sum(h for _, h in sizes) + STACK_GAP * (len(sizes) - 1) + 2 * GROUP_PAD + GROUP_TITLE
    return (width, height)


def _stacked(frame: Box, members: Sequence[tuple[str, tuple[float, float]]]) -> dict[str, Point]:
    """The centres of a frame's members, top to bottom below its title."""
    centres: dict[str, Point] = {}
    y = frame.y + GROUP_PAD + GROUP_TITLE
    for member, (_, h) in members:
        centres[member] = (frame.x + frame.w / 2, y + h / 2)
        y += h + STACK_GAP
    return centres


def _overlaps(a: Box, b: Box) -> bool:
    return a.x < b.x + b.w and b.x < a.x + a.w and a.y < b.y + b.h and b.y < a.y + a.h


def _place_part(part: object, layer_gap: float, vertex_gap: float) -> dict[str, Point]:
    """Centres of one connected part's vertices, turned to run left to right."""
    sug = SugiyamaLayout(part)
    sug.xspace = vertex_gap
    sug.yspace = layer_gap
    sug.init_all()
    sug.draw(3)
    return {str(v.data): (v.view.xy[1], v.view.xy[0]) for v in part.sV}  # type: ignore[attr-defined]


def _turn(points: Sequence[Point]) -> list[Point]:
    return [(y, x) for x, y in points]


def _edge_path(scene: Scene, index: int, boxes: dict[str, Box], kinds: dict[str, Kind],
               routes: dict[tuple[str, str], list[Point]], placed_as: dict[str, str]) -> tuple[Point, ...]:
    edge = scene.edges[index]
    source, target = boxes[edge.source], boxes[edge.target]
    if edge.source == edge.target:
        x = source.centre[0]
        top = source.y
        return ((x - source.w / 4, top + 2), (x - source.w / 4, top - LOOP), (x + source.w / 4, top - LOOP),
                (x + source.w / 4, top + 2))
    source_at, target_at = placed_as[edge.source], placed_as[edge.target]  # a member's route is its frame's
    route = routes.get((source_at, target_at))
    if route is None:
        reverse = routes.get((target_at, source_at))
        route = list(reversed(reverse)) if reverse else [source.centre, target.centre]
    route = [source.centre, *route[1:-1], target.centre]
    # parallel edges (two topics between the same nodes, either way) bow apart around the
    # middle, each to its own side as seen going from the lesser vertex id to the greater
    twins = [i for i, e in enumerate(scene.edges) if {e.source, e.target} == {edge.source, edge.target}]
    rank = twins.index(index)
    if len(twins) > 1:
        offset = (rank - (len(twins) - 1) / 2) * TWIN_GAP
        if edge.source > edge.target:  # its route runs the other way: so does its normal
            offset = -offset
        if offset:
            route = _bow(route, offset)
    start = _clip(route[1], source, kinds[edge.source])
    end = _clip(route[-2], target, kinds[edge.target])
    return (start, *route[1:-1], end)


def _bow(route: list[Point], offset: float) -> list[Point]:
    (x0, y0), (x1, y1) = route[0], route[-1]
    length = math.hypot(x1 - x0, y1 - y0) or 1.0
    nx, ny = -(y1 - y0) / length, (x1 - x0) / length
    if len(route) == 2:
        return [route[0], ((x0 + x1) / 2 + nx * offset, (y0 + y1) / 2 + ny * offset), route[1]]
    return [route[0], *((x + nx * offset, y + ny * offset) for x, y in route[1:-1]), route[-1]]


def _clip(towards: Point, box: Box, kind: Kind) -> Point:
    """Where the line from the box's centre to `towards` leaves the shape."""
    cx, cy = box.centre
    dx, dy = towards[0] - cx, towards[1] - cy
    if dx == 0 and dy == 0:
        return (cx, cy)
    a, b = box.w / 2, box.h / 2
    if kind is Kind.NODE:
        scale = 1.0 / math.sqrt((dx / a) ** 2 + (dy / b) ** 2)
    else:
        scale = min(a / abs(dx) if dx else math.inf, b / abs(dy) if dy else math.inf)
    return (cx + dx * min(scale, 1.0), cy + dy * min(scale, 1.0))


def cubic_segments(points: Sequence[Point]) -> list[tuple[Point, Point, Point]]:
    """A smooth curve through `points` as cubic Bezier segments (control, control, end) from the
    first point: Catmull-Rom, so the curve passes through every routing point."""
    segments: list[tuple[Point, Point, Point]] = []
    for i in range(len(points) - 1):
        p0 = points[i - 1] if i > 0 else points[i]
        p1, p2 = points[i], points[i + 1]
        p3 = points[i + 2] if i + 2 < len(points) else p2
        c1 = (p1[0] + (p2[0] - p0[0]) / 6, p1[1] + (p2[1] - p0[1]) / 6)
        c2 = (p2[0] - (p3[0] - p1[0]) / 6, p2[1] - (p3[1] - p1[1]) / 6)
        segments.append((c1, c2, p2))
    return segments
