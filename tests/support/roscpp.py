"""Compiled roscpp peers for interop tests (tests/interop/cpp/*.cpp), built once per source version.

The binaries are cached under the system temp dir, keyed by a digest of the sources and the
compiler flags, so a test run pays for g++ only when a source changed.
"""

from __future__ import annotations

import hashlib
import os
import shutil
import subprocess
import tempfile
from pathlib import Path

CPP = Path(__file__).resolve().parents[1] / "interop" / "cpp"


def roscpp_flags() -> list[str] | None:
    """The compiler and linker flags for roscpp + std_msgs, or None if they are not installed."""
    if shutil.which("g++") is None or shutil.which("pkg-config") is None:
        return None
    result = subprocess.run(["pkg-config", "--cflags", "--libs", "roscpp", "std_msgs"], capture_output=True,
                            text=True)
    if result.returncode != 0 or not Path("/usr/include/ros/ros.h").exists():
        return None
    return result.stdout.split()


def build_peers(flags: list[str]) -> dict[str, Path]:
    """Every tests/interop/cpp/<name>.cpp compiled, by name."""
    sources = sorted(CPP.glob("*.cpp"))
    digest = hashlib.sha256(b"".join(p.read_bytes() for p in sources) + " ".join(flags).encode()).hexdigest()[:16]
    build = Path(tempfile.gettempdir()) / f"kame-roscpp-peers-{digest}"
    build.mkdir(exist_ok=True)
    built = {}
    for source in sources:
        target = build / source.stem
        if not target.exists():
            partial = build / f"{source.stem}.{os.getpid()}.tmp"  # atomic: parallel runs never see half a file
            subprocess.run(["g++", "-O1", "-std=c++17", "-o", str(partial), str(source), *flags], check=True,
                           capture_output=True, timeout=300)
            partial.replace(target)
        built[source.stem] = target
    return built
