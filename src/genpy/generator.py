"""genpy.generator: message and service modules written into a package's build, as catkin's
genpy step calls them (MsgGenerator().generate_messages(package, files, outdir, search_path)),
with kame's codegen (kame.msg.build): the modules are those kame-genmsg writes.

`search_path` maps package names to their msg/ (or srv/) folders, as genmsg gives it; types
it does not name come from the packages kame ships.
"""

from __future__ import annotations

import os
import sys
from collections.abc import Callable, Iterable, Mapping
from pathlib import Path

from genpy.base import SIMPLE_TYPES, is_simple
from genpy.generate_numpy import NUMPY_DTYPE, pack_numpy, unpack_numpy
from genpy.generate_struct import (
    clear_patterns,
    compute_struct_pattern,
    get_patterns,
    int32_pack,
    int32_unpack,
    pack,
    pack2,
    reduce_pattern,
    unpack,
    unpack2,
    unpack3,
)
from kame.msg.build import message_module, service_module
from kame.msg.catalog import SHARE_DIR, MsgCatalog, Package, find_packages
from kame.msg.codegen import python_name
from kame.msg.errors import MessageError
from kame.msg.parser import is_legal_base_name

__all__ = ["NUMPY_DTYPE", "SIMPLE_TYPES", "Generator", "MsgGenerationException", "MsgGenerator", "SrvGenerator",
           "clear_patterns", "compute_outfile_name", "compute_resource_name", "compute_struct_pattern",
           "get_patterns", "int32_pack", "int32_unpack", "is_simple", "pack", "pack2", "pack_numpy",
           "reduce_pattern", "unpack", "unpack2", "unpack3", "unpack_numpy"]


class MsgGenerationException(Exception):
    """A package or definition that cannot be generated."""


def compute_resource_name(filename: str, ext: str) -> str:
    """'/path/to/Foo.msg', '.msg' -> 'Foo'."""
    return os.path.basename(filename)[:-len(ext)]


def compute_outfile_name(outdir: str, infile_name: str, ext: str) -> str:
    """The generated module's path: a leading `_` keeps it from shadowing the class name."""
    return os.path.join(outdir, "_" + compute_resource_name(infile_name, ext) + ".py")


def _remap_reserved(field_name: str) -> str:
    """A field named like a Python keyword gets genpy's trailing underscore."""
    return python_name(field_name)


def _catalog(package: str, package_files: Iterable[str], search_path: Mapping[str, Iterable[str]]) -> MsgCatalog:
    packages = dict(find_packages([SHARE_DIR]))
    for name, folders in search_path.items():
        for folder in folders:
            packages[name] = Package(name, Path(folder).resolve().parent)
            break
    for file in package_files:  # <package>/msg/Foo.msg: the package is two folders up
        packages.setdefault(package, Package(package, Path(file).resolve().parent.parent))
    return MsgCatalog(packages)


class Generator:
    """Writes one module per interface file of a package into `outdir`."""

    def __init__(self, what: str, ext: str, module_fn: Callable[[MsgCatalog, str, str], str]) -> None:
        self.what = what
        self.ext = ext
        self.module_fn = module_fn

    def generate(self, catalog: MsgCatalog, full_type: str, f: str, outdir: str) -> str:
        os.makedirs(outdir, exist_ok=True)
        outfile = compute_outfile_name(outdir, os.path.basename(f), self.ext)
        text = self.module_fn(catalog, full_type, os.path.basename(f))
        Path(outfile).write_text(text, encoding="utf-8")
        return outfile

    def generate_messages(self, package: str, package_files: Iterable[str], outdir: str,
                          search_path: Mapping[str, Iterable[str]]) -> int:
        """0, or 1 when a file could not be generated (each failure said on stderr, as genpy does)."""
        if not is_legal_base_name(package):
            raise MsgGenerationException(
                f"\nERROR: package name '{package}' is illegal and cannot be used in message generation.\n"
                "Please see http://ros.org/wiki/Names")
        files = [os.path.abspath(f) for f in package_files]
        catalog = _catalog(package, files, search_path)
        retcode = 0
        for f in files:
            try:
                self.generate(catalog, f"{package}/{compute_resource_name(f, self.ext)}", f, outdir)
            except (MessageError, OSError) as exc:
                print(f"\nERROR: Unable to generate {self.what} for package '{package}': while processing '{f}': "
                      f"{exc}\n", file=sys.stderr)
                retcode = 1
        return retcode


class MsgGenerator(Generator):
    """Message modules (`_Foo.py` for each `msg/Foo.msg`)."""

    def __init__(self) -> None:
        super().__init__("messages", ".msg", message_module)


class SrvGenerator(Generator):
    """Service modules (`_Foo.py` for each `srv/Foo.srv`: Foo, FooRequest, FooResponse)."""

    def __init__(self) -> None:
        super().__init__("services", ".srv", service_module)
