"""genpy.generate_numpy: the code-text helpers for numpy arrays in genpy-style generated code
(kame's codegen has its own numpy paths; see genpy.generate_struct)."""

from __future__ import annotations

from genpy.generate_struct import serialize

__all__ = ["NUMPY_DTYPE", "pack_numpy", "unpack_numpy"]

NUMPY_DTYPE: dict[str, str] = {
    "float32": "numpy.float32", "float64": "numpy.float64", "bool": "numpy.bool",
    "int8": "numpy.int8", "int16": "numpy.int16", "int32": "numpy.int32", "int64": "numpy.int64",
    "uint8": "numpy.uint8", "uint16": "numpy.uint16", "uint32": "numpy.uint32", "uint64": "numpy.uint64",
    "char": "numpy.uint8", "byte": "numpy.int8",  # the deprecated aliases
}


def unpack_numpy(var: str, count: str, dtype: str, buff: str) -> str:
    return f"{var} = numpy.frombuffer({buff}, dtype={dtype}, count={count})"


def pack_numpy(var: str) -> str:
    return serialize(f"{var}.tostring()")  # the text of Noetic's genpy 0.6.16
