"""rqt_graph's drawings as files: SVG from a layout, and graphviz dot text from a scene (pure).

The SVG draws what the window draws (nodes as ellipses, topics as boxes, namespace clusters,
edges with arrowheads and, in nodes-only mode, topic labels); each shape carries a class
(`node`, `topic`, `edge`, `cluster`) and a <title> with its name, so programs can read it.
The dot text is rqt_graph's "Save as DOT" (rankdir=LR), for graphviz and other tools.
"""

from __future__ import annotations

from xml.sax.saxutils import escape

from kame.rqt.graph_layout import FONT_SIZE, Layout, cubic_segments
from kame.rqt.graph_model import Kind, Scene

NODE_FILL = "#ffffff"
UNREACHABLE = "#cc0000"
TOPIC_FILL = "#ffffff"
INK = "#000000"
CLUSTER = "#6b7a8f"


def _f(value: float) -> str:
    return f"{value:.1f}".rstrip("0").rstrip(".")


def path_data(points: tuple[tuple[float, float], ...]) -> str:
    parts = [f"M{_f(points[0][0])},{_f(points[0][1])}"]
    for c1, c2, end in cubic_segments(points):
        parts.append(f"C{_f(c1[0])},{_f(c1[1])} {_f(c2[0])},{_f(c2[1])} {_f(end[0])},{_f(end[1])}")
    return " ".join(parts)


def to_svg(layout: Layout) -> str:
    scene = layout.scene
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{_f(layout.width)}" height="{_f(layout.height)}" '
           f'viewBox="0 0 {_f(layout.width)} {_f(layout.height)}" font-family="sans-serif" '
           f'font-size="{_f(FONT_SIZE)}">',
           "<defs><marker id=\"arrow\" viewBox=\"0 0 10 10\" refX=\"10\" refY=\"5\" markerWidth=\"8\" "
           "markerHeight=\"8\" orient=\"auto-start-reverse\"><path d=\"M0,0 L10,5 L0,10 z\" fill=\"#000\"/>"
           "</marker></defs>",
           '<rect width="100%" height="100%" fill="#ffffff"/>']
    for namespace, box in sorted(layout.groups.items()):
        out.append(f'<g class="cluster"><title>{escape(namespace)}</title>'
                   f'<rect x="{_f(box.x)}" y="{_f(box.y)}" width="{_f(box.w)}" height="{_f(box.h)}" rx="6" '
                   f'fill="#f4f6fa" stroke="{CLUSTER}" stroke-dasharray="4 2"/>'
                   f'<text x="{_f(box.x + 6)}" y="{_f(box.y + 13)}" fill="{CLUSTER}">{escape(namespace)}</text>'
                   '</g>')
    for index, edge in enumerate(scene.edges):
        source, target = scene.vertex(edge.source).name, scene.vertex(edge.target).name
        title = f"{source}->{target}" + (f" [{edge.label}]" if edge.label else "")
        out.append(f'<g class="edge"><title>{escape(title)}</title><path d="{path_data(layout.paths[index])}" '
                   f'fill="none" stroke="{INK}" marker-end="url(#arrow)"/>')
        if edge.label:
            box = layout.labels[index]
            out.append(f'<text x="{_f(box.x + box.w / 2)}" y="{_f(box.y + FONT_SIZE)}" '
                       f'text-anchor="middle">{escape(edge.label)}</text>')
        out.append("</g>")
    for vertex in scene.vertices:
        box = layout.boxes[vertex.id]
        cx, cy = box.centre
        stroke = UNREACHABLE if vertex.unreachable else INK
        if vertex.kind is Kind.NODE:
            shape = (f'<ellipse cx="{_f(cx)}" cy="{_f(cy)}" rx="{_f(box.w / 2)}" ry="{_f(box.h / 2)}" '
                     f'fill="{NODE_FILL}" stroke="{stroke}"/>')
        else:
            shape = (f'<rect x="{_f(box.x)}" y="{_f(box.y)}" width="{_f(box.w)}" height="{_f(box.h)}" '
                     f'fill="{TOPIC_FILL}" stroke="{stroke}"/>')
        out.append(f'<g class="{vertex.kind.value}"><title>{escape(vertex.name)}</title>{shape}'
                   f'<text x="{_f(cx)}" y="{_f(cy + FONT_SIZE / 3)}" text-anchor="middle">{escape(vertex.name)}</text>'
                   "</g>")
    out.append("</svg>\n")
    return "\n".join(out)


def to_dot(scene: Scene) -> str:
    lines = ["digraph graphname {", '  graph [rankdir=LR];', '  node [label="\\N"];']
    grouped = {member for group in scene.groups for member in group.members}
    for index, group in enumerate(scene.groups):
        lines.append(f"  subgraph cluster_{index} {{")
        lines.append(f"    label={_quote(group.namespace)};")
        lines += [f"    {_vertex_line(scene, member)}" for member in group.members]
        lines.append("  }")
    lines += [f"  {_vertex_line(scene, v.id)}" for v in scene.vertices if v.id not in grouped]
    for edge in scene.edges:
        label = f" [label={_quote(edge.label)}]" if edge.label else ""
        lines.append(f"  {_quote(edge.source)} -> {_quote(edge.target)}{label};")
    lines.append("}")
    return "\n".join(lines) + "\n"


def _vertex_line(scene: Scene, vertex_id: str) -> str:
    vertex = scene.vertex(vertex_id)
    shape = "ellipse" if vertex.kind is Kind.NODE else "box"
    colour = ', color="red"' if vertex.unreachable else ""
    return f"{_quote(vertex.id)} [label={_quote(vertex.name)}, shape={shape}{colour}];"


def _quote(text: str) -> str:
    """A dot ID in double quotes."""
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"') + '"'
