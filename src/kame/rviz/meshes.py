"""Mesh resources for Marker MESH_RESOURCE and URDF mesh visuals: STL (binary and ASCII) and
Collada (.dae) files read by trimesh into triangles, with the colours the file gives.

Rules (rviz's resource retriever):
- `package://pkg/path` is the file `path` in package `pkg` (found by the finder the window
  passes in); `file:///abs/path` and a plain absolute path are that file.
- A file is read once; later uses (and failures: the reason is kept) come from the cache.
- A Collada scene's node transforms are applied; its materials' colours become per-vertex
  colours (used when the marker asks for embedded materials, or the URDF gives none).
- An STL file is checked as rviz's STLLoader checks it before trimesh sees it: a binary one
  whose triangle count disagrees with its size, or that has no triangles, is refused with the
  reason (trimesh would read it as ASCII, find nothing or ask for charset_normalizer, an
  optional module, to guess the text's encoding); data past the count is left out, as rviz
  does. ASCII STL, which rviz does not read, must be text.
"""

from __future__ import annotations

import os
import struct
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from kame.rviz.scene import Color, Scene, apply

FORMATS = {".stl": "stl", ".dae": "dae"}
# rviz's RVIZ/ShadedRed, its material for a robot part whose URDF gives no colour (and a mesh
# without colours of its own), as Debian's rviz draws kame's TurtleBot (tests/stage/test_debian_rviz.py)
DEFAULT_COLOR: Color = (1.0, 0.0, 0.0, 1.0)


@dataclass(frozen=True)
class Mesh:
    triangles: np.ndarray  # (3 N) x 3 float32, the file's own coordinates
    colors: np.ndarray | None  # (3 N) x 4 float32, None when the file gives none


class MeshLibrary:
    def __init__(self, find_package: Callable[[str], str | None] | None = None) -> None:
        self.find_package = find_package
        self._cache: dict[str, Mesh | str] = {}

    def path(self, uri: str) -> str:
        """The file `uri` names; ValueError saying why when there is none."""
        if uri.startswith("package://"):
            package, _, rest = uri[len("package://"):].partition("/")
            found = self.find_package(package) if self.find_package is not None else None
            if not found:
                raise ValueError(f"package [{package}] not found for {uri}")
            return os.path.join(found, rest)
        if uri.startswith("file://"):
            return uri[len("file://"):]
        if os.path.isabs(uri):
            return uri
        raise ValueError(f"cannot resolve mesh resource {uri!r} (package://, file:// or an absolute path)")

    def load(self, uri: str) -> Mesh | str:
        """The mesh `uri` names, or why it cannot be drawn."""
        if uri not in self._cache:
            self._cache[uri] = self._read(uri)
        return self._cache[uri]

    def _read(self, uri: str) -> Mesh | str:
        try:
            path = self.path(uri)
        except ValueError as exc:
            return str(exc)
        kind = FORMATS.get(os.path.splitext(path)[1].lower())
        if kind is None:
            return f"mesh format of {uri} is not read (STL and DAE are)"
        try:
            with open(path, "rb") as f:
                return read_mesh(f.read(), kind)
        except OSError as exc:
            return f"cannot read mesh {uri}: {exc.strerror or exc}"
        except Exception as exc:  # a malformed file: trimesh's and pycollada's parse errors
            return f"cannot read mesh {uri}: {exc}"


_STL_HEADER = 84  # an 80-byte comment and a uint32 triangle count
_STL_TRIANGLE = 50  # a normal and three corners (12 float32) and a uint16 attribute count


def checked_stl(data: bytes) -> bytes:
    """The STL file's bytes as trimesh can read them; ValueError naming what is wrong otherwise.
    A file whose size matches its binary triangle count is binary (a binary header may start
    with `solid` too); else one that starts with `solid` and has `endsolid` is ASCII; anything
    else is a binary file that lies about its size."""
    count = struct.unpack_from("<I", data, 80)[0] if len(data) >= _STL_HEADER else -1
    expected = _STL_HEADER + count * _STL_TRIANGLE
    if len(data) != expected and data.startswith(b"solid") and b"endsolid" in data[5:]:
        try:
            data.decode("utf-8")
        except UnicodeDecodeError as exc:
            raise ValueError(f"malformed ASCII STL: byte {exc.start} is not text") from None
        return data
    if count < 0:
        raise ValueError(f"malformed STL: {len(data)} bytes, too short for a binary STL's 80-byte header "
                         "and triangle count, and not an ASCII STL (solid ... endsolid)")
    if count == 0:
        raise ValueError("the STL file has no triangles (its binary header says 0)")
    if len(data) < expected:
        raise ValueError(f"malformed STL: its binary header says {count} triangles ({expected} bytes), "
                         f"but the file has {len(data)} bytes")
    return data[:expected]


def read_mesh(data: bytes, kind: str) -> Mesh:
    """The triangles (and colours) of an STL or DAE file's bytes."""
    import io

    import trimesh

    if kind == "stl":
        data = checked_stl(data)

    scene = trimesh.load(io.BytesIO(data), file_type=kind, force="scene")
    if not isinstance(scene, trimesh.Scene):
        raise ValueError(f"not a {kind.upper()} scene")
    triangles: list[np.ndarray] = []
    colors: list[np.ndarray] = []
    any_color = False
    parts: list[Any] = scene.dump()  # each part with its scene node's transform applied
    for geometry in parts:
        if not hasattr(geometry, "faces") or not len(geometry.faces):
            continue
        corners = np.asarray(geometry.triangles, dtype=np.float32).reshape(-1, 3)
        triangles.append(corners)
        face_colors = _face_colors(geometry)
        any_color = any_color or face_colors is not None
        if face_colors is None:
            face_colors = np.ones((len(geometry.faces), 4), dtype=np.float32)
        colors.append(np.repeat(face_colors, 3, axis=0))
    if not triangles:
        return Mesh(np.zeros((0, 3), np.float32), None)
    return Mesh(np.concatenate(triangles), np.concatenate(colors) if any_color else None)


def _face_colors(geometry: Any) -> np.ndarray | None:
    visual = getattr(geometry, "visual", None)
    if visual is None:
        return None
    if getattr(visual, "kind", None) == "texture":  # a textured material: its main colour
        material = getattr(visual, "material", None)
        main = getattr(material, "main_color", None)
        if main is None:
            return None
        count = len(geometry.faces)
        return np.tile(np.asarray(main, dtype=np.float32) / 255.0, (count, 1))
    if not getattr(visual, "defined", False):
        return None
    return np.asarray(visual.face_colors, dtype=np.float32) / 255.0


def add_mesh(scene: Scene, mesh: Mesh, matrix: np.ndarray, scale: tuple[float, float, float],
             color: Color | None, alpha: float = 1.0) -> None:
    """`mesh` scaled, placed at `matrix`, in `color` (its own colours when None and it has some)."""
    corners = mesh.triangles * np.asarray(scale, dtype=np.float32)
    if color is None and mesh.colors is not None:
        colors = mesh.colors.copy()
        colors[:, 3] *= alpha
    else:
        r, g, b, a = color or DEFAULT_COLOR
        colors = np.array((r, g, b, a * alpha), dtype=np.float32)
    scene.add("triangles", apply(matrix, corners), colors)
