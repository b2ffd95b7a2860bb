"""genpy.generate_initpy: the `__init__.py` of a generated msg/ or srv/ folder, importing each
generated module (`from ._String import *`), as catkin's genpy step writes it with --initpy."""

from __future__ import annotations

import os
from collections.abc import Iterable

from genmsg import MsgGenerationException

__all__ = ["MsgGenerationException", "write_module", "write_modules"]


def write_modules(outdir: str) -> int:
    """Write `outdir`'s __init__.py for the `_Type.py` modules in it; 0 (nothing written when
    there is no such folder)."""
    if not os.path.isdir(outdir):
        return 0
    types_in_dir = {f[1:-3] for f in os.listdir(outdir) if f.endswith(".py") and f != "__init__.py"}
    write_module(outdir, ["_" + name for name in sorted(types_in_dir)])
    return 0


def write_module(basedir: str, generated_modules: Iterable[str]) -> None:
    """`basedir`/__init__.py importing everything from each module, the folder made if need be;
    MsgGenerationException when a file stands where the folder should be."""
    if not os.path.exists(basedir):
        os.makedirs(basedir)
    elif not os.path.isdir(basedir):
        raise MsgGenerationException(f"file preventing the creating of module directory: {basedir}")
    with open(os.path.join(basedir, "__init__.py"), "w") as f:
        for mod in generated_modules:
            f.write(f"from .{mod} import *\n")
