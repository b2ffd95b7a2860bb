"""Mesh files (STL, Collada .dae, Wavefront .obj) as MuJoCo takes them: vertices and faces.

Read by rviz's loader (kame.rviz.meshes.read_mesh, trimesh underneath), so a mesh looks the same
in both; each file is read once per world. A missing or unreadable file is a GazeboError naming it.
"""

from __future__ import annotations

import os

import numpy as np

from kame.gazebo.description import Geometry
from kame.gazebo.errors import GazeboError
from kame.rviz.meshes import read_mesh

FORMATS = {".stl": "stl", ".dae": "dae", ".obj": "obj"}


class MeshCache:
    def __init__(self) -> None:
        self._loaded: dict[str, tuple[np.ndarray, np.ndarray]] = {}

    def load(self, geometry: Geometry) -> tuple[np.ndarray, np.ndarray]:
        """The vertices (N x 3) and triangles (M x 3 indices) of the geometry's mesh file."""
        path = geometry.mesh_file
        if path not in self._loaded:
            self._loaded[path] = _read(path, geometry.mesh_uri)
        return self._loaded[path]

    def triangles(self, geometry: Geometry) -> np.ndarray:
        """The mesh's triangles' corners (3 M x 3), scaled as the geometry says."""
        vertices, faces = self.load(geometry)
        corners: np.ndarray = (vertices[faces.ravel()] * np.asarray(geometry.scale)).astype(np.float32)
        return corners


def _read(path: str, uri: str) -> tuple[np.ndarray, np.ndarray]:
    kind = FORMATS.get(os.path.splitext(path)[1].lower())
    if kind is None:
        raise GazeboError(f"mesh {uri}: the format of {path} is not read (STL, DAE and OBJ are)")
    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError as exc:
        raise GazeboError(f"mesh {uri}: cannot read {path}: {exc.strerror or exc}") from None
    try:
        mesh = read_mesh(data, kind)
    except Exception as exc:  # a malformed file: trimesh's and pycollada's parse errors
        raise GazeboError(f"mesh {uri}: cannot read {path}: {exc}") from None
    if len(mesh.triangles) == 0:
        raise GazeboError(f"mesh {uri}: {path} has no triangles")
    vertices, inverse = np.unique(mesh.triangles.astype(np.float64), axis=0, return_inverse=True)
    faces = inverse.reshape(-1, 3).astype(np.int32)
    return vertices, faces
