"""roscpp_tutorials built from kame's C++ sources with the system's toolchain, once per source version.

Rules:
- The package is assembled in CACHE/src/roscpp_tutorials (CMakeLists.txt and src/ from
  kame/roscpp_tutorials/cpp; package.xml and srv/ from kame/share/roscpp_tutorials), then
  configured and made as `catkin build` makes one package (kame/catkin/cmake.py) into
  CACHE/devel: the programs are CACHE/devel/lib/roscpp_tutorials/NAME.
- CACHE is $XDG_CACHE_HOME/kame/roscpp_tutorials-DIGEST (XDG_CACHE_HOME defaults to
  ~/.cache), DIGEST that of the sources: changed sources build anew.
- One build at a time: a process that wants the programs while another builds them waits on
  the lock (flock) and then finds them built.
- The build's output is CACHE/build.log. A failed build is remembered (CACHE/FAILED) and not
  retried until the sources change: the ports run instead.
"""

from __future__ import annotations

import fcntl
import hashlib
import shutil
import sys
from collections.abc import Mapping
from pathlib import Path

from kame.catkin.cmake import CMakeBuild, CMakeFailed
from kame.catkin.toolchain import Toolchain, find_toolchain
from kame.msg.catalog import SHARE_DIR

PACKAGE = "roscpp_tutorials"
SOURCES = Path(__file__).resolve().parent / "cpp"
SHARED = SHARE_DIR / PACKAGE


def _inputs() -> list[Path]:
    return sorted([SOURCES / "CMakeLists.txt", *SOURCES.glob("src/*.cpp"), SHARED / "package.xml",
                   *SHARED.glob("srv/*.srv")])


def cache_dir(env: Mapping[str, str]) -> Path:
    digest = hashlib.sha256()
    for path in _inputs():
        digest.update(path.name.encode() + b"\0" + path.read_bytes())
    base = Path(env.get("XDG_CACHE_HOME") or Path(env.get("HOME", "~")).expanduser() / ".cache")
    return base / "kame" / f"{PACKAGE}-{digest.hexdigest()[:16]}"


def _assemble(source: Path) -> None:
    if source.exists():
        shutil.rmtree(source)
    (source / "src").mkdir(parents=True)
    shutil.copy2(SOURCES / "CMakeLists.txt", source / "CMakeLists.txt")
    for cpp in SOURCES.glob("src/*.cpp"):
        shutil.copy2(cpp, source / "src" / cpp.name)
    shutil.copy2(SHARED / "package.xml", source / "package.xml")
    shutil.copytree(SHARED / "srv", source / "srv")


def _build(cache: Path, toolchain: Toolchain, env: Mapping[str, str]) -> bool:
    source = cache / "src" / PACKAGE
    _assemble(source)
    log = cache / "build.log"
    log.unlink(missing_ok=True)
    print(f"kame: building {PACKAGE} from its C++ sources with this machine's roscpp (once; log: {log})",
          file=sys.stderr, flush=True)
    cmake = CMakeBuild(toolchain, source, cache / "build", cache / "devel", cache / "install", env, [],
                       lambda _line: None, False, log)
    try:
        cmake.configure(None, [])
        cmake.make([], [])
    except CMakeFailed:
        (cache / "FAILED").write_text(f"see {log}\n")
        print(f"kame: building {PACKAGE} failed (see {log}); running kame's ports instead",
              file=sys.stderr, flush=True)
        return False
    (cache / "BUILT").write_text("")
    return True


def program(name: str, env: Mapping[str, str]) -> Path | None:
    """The compiled program `name`, built first if need be; None where it cannot be built here."""
    cache = cache_dir(env)
    binary = cache / "devel" / "lib" / PACKAGE / name
    if (cache / "BUILT").exists():
        return binary if binary.is_file() else None
    if (cache / "FAILED").exists():
        return None
    toolchain = find_toolchain(env)
    if not isinstance(toolchain, Toolchain):
        return None
    cache.mkdir(parents=True, exist_ok=True)
    with open(cache.with_suffix(".lock"), "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)  # a build running in another process: wait for its end
        try:
            if not (cache / "BUILT").exists() and not (cache / "FAILED").exists():
                _build(cache, toolchain, env)
        finally:
            fcntl.flock(lock, fcntl.LOCK_UN)
    return binary if (cache / "BUILT").exists() and binary.is_file() else None


def disabled(env: Mapping[str, str]) -> bool:
    """KAME_CPP_TUTORIALS=port runs the ports even where the programs can be built."""
    return env.get("KAME_CPP_TUTORIALS", "") == "port"
