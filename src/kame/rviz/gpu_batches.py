"""The OpenGL buffers behind the 3-D view's Scene: a set for each batch, by its place in the
scene. An unchanged batch is not uploaded again; a new one goes into its slot's buffers
(glBufferSubData while it fits, so a cloud's buffers are allocated once). Needs the view's GL
context current: the view calls it from its paint."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from OpenGL import GL

from kame.rviz.scene import Batch, face_normals


@dataclass
class GpuBatch:
    batch: Batch | None  # what the buffers hold now
    vertices: int
    colors: int
    normals: int  # triangles' only
    indices: int  # an indexed batch's only
    vertex_bytes: int = 0  # the buffers' sizes
    color_bytes: int = 0
    normal_bytes: int = 0
    index_bytes: int = 0


def _upload(target: int, buffer: int, data: np.ndarray, capacity: int) -> int:
    """`data` into the GL buffer, reusing its storage when it fits; the buffer's size after."""
    data = np.ascontiguousarray(data)
    GL.glBindBuffer(target, buffer)
    if data.nbytes <= capacity:
        GL.glBufferSubData(target, 0, data.nbytes, data)
        return capacity
    GL.glBufferData(target, data.nbytes, data, GL.GL_DYNAMIC_DRAW)
    return data.nbytes


class GpuBatches:
    def __init__(self) -> None:
        self._slots: list[GpuBatch] = []

    def uploaded(self, slot: int, batch: Batch) -> GpuBatch:
        """The slot-th batch's buffers, holding `batch`. Leaves GL_ELEMENT_ARRAY_BUFFER unbound:
        Qt's painter draws the labels with indices of its own."""
        if slot == len(self._slots):
            self._slots.append(GpuBatch(None, *(int(b) for b in GL.glGenBuffers(4))))
        known = self._slots[slot]
        if known.batch is batch:
            return known
        known.vertex_bytes = _upload(GL.GL_ARRAY_BUFFER, known.vertices, batch.vertices, known.vertex_bytes)
        if not batch.uniform:
            known.color_bytes = _upload(GL.GL_ARRAY_BUFFER, known.colors, batch.colors, known.color_bytes)
        if batch.kind == "triangles":
            normals = face_normals(batch.vertices) if batch.normals is None else batch.normals
            known.normal_bytes = _upload(GL.GL_ARRAY_BUFFER, known.normals, normals, known.normal_bytes)
        if batch.indices is not None:
            known.index_bytes = _upload(GL.GL_ELEMENT_ARRAY_BUFFER, known.indices, batch.indices, known.index_bytes)
            GL.glBindBuffer(GL.GL_ELEMENT_ARRAY_BUFFER, 0)
        known.batch = batch
        return known

    def keep(self, count: int) -> None:
        """Frees the buffers of the slots from `count` on (the scene has fewer batches now)."""
        for unused in self._slots[count:]:
            GL.glDeleteBuffers(4, [unused.vertices, unused.colors, unused.normals, unused.indices])
        del self._slots[count:]
