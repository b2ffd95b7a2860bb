"""Mesh files that cannot be drawn: the reason shown is the file's fault, named as rviz names it."""

from __future__ import annotations

import struct
from pathlib import Path

import pytest

from kame.rviz.meshes import Mesh, MeshLibrary

trimesh = pytest.importorskip("trimesh", reason="rviz reads meshes with trimesh (kame[gui])")


def load(tmp_path: Path, name: str, data: bytes) -> Mesh | str:
    path = tmp_path / name
    path.write_bytes(data)
    return MeshLibrary().load(f"file://{path}")


def binary_stl(triangles: int, header: bytes = b"") -> bytes:
    body = b"".join(struct.pack("<12fH", 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0) for _ in range(triangles))
    return header.ljust(80, b"\0") + struct.pack("<I", triangles) + body


def test_a_binary_stl_whose_count_lies_names_its_count_and_size(tmp_path: Path) -> None:
    # trimesh read it as ASCII and the window showed "No module named 'charset_normalizer'"
    for data in (binary_stl(2)[:-10], b"\0" * 80 + struct.pack("<I", 100_000_000) + b"\x01" * 30):
        count = struct.unpack_from("<I", data, 80)[0]
        assert load(tmp_path, "liar.stl", data) == (
            f"cannot read mesh file://{tmp_path}/liar.stl: malformed STL: its binary header says {count} "
            f"triangles ({84 + 50 * count} bytes), but the file has {len(data)} bytes")


def test_an_stl_with_no_triangles_says_so(tmp_path: Path) -> None:
    assert load(tmp_path, "empty.stl", binary_stl(0)) == (
        f"cannot read mesh file://{tmp_path}/empty.stl: the STL file has no triangles (its binary header says 0)")


def test_a_file_too_short_for_a_header_and_ascii_that_is_not_text(tmp_path: Path) -> None:
    assert "malformed STL: 3 bytes, too short for a binary STL's 80-byte header" in str(load(tmp_path, "a.stl", b"abc"))
    not_text = load(tmp_path, "b.stl", b"solid x\n\xff\nendsolid x\n")
    assert str(not_text).endswith("malformed ASCII STL: byte 8 is not text")


def test_a_binary_stl_headed_solid_or_with_trailing_bytes_is_read_as_rviz_reads_it(tmp_path: Path) -> None:
    mesh = load(tmp_path, "solid.stl", binary_stl(2, header=b"solid exported by a CAD tool endsolid"))
    assert not isinstance(mesh, str) and mesh.triangles.shape == (6, 3)
    mesh = load(tmp_path, "long.stl", binary_stl(2) + b"trailing junk")
    assert not isinstance(mesh, str) and mesh.triangles.shape == (6, 3)
