"""Whether one of kame's simulators can open its window here, asked before it tries: with no
display, without PySide6, or when a probe child finds that Qt cannot open its platform (a
missing system library, a Qt binding known to crash), the simulation runs headless and says
why once. The probe is a child process because Qt aborts a process whose platform plugin
cannot load, and the simulation must not be that process.
"""

from __future__ import annotations

import importlib.util
import platform
import sys
from collections.abc import Mapping
from dataclasses import dataclass

from kame.net.command import run_command
from kame.turtlesim.window_probe import headless_words, window_verdict

WINDOW_PROBE_SECONDS = 20.0  # Qt starts in well under a second; a loaded machine gets slack


@dataclass(frozen=True)
class NoWindow:
    reason: str  # said once
    asked_for: bool  # a headless option or no display (an INFO line), else something is wrong (a WARN)


def window_problem(program: str, headless_option: str | None, env: Mapping[str, str]) -> NoWindow | None:
    """Why `program` will have no window, or None when Qt can open one. `headless_option` is the
    command-line option the user gave to ask for none (None when not given)."""
    if headless_option is not None:
        return NoWindow(f"{headless_option}: {program} runs without a window", True)
    if not (env.get("DISPLAY") or env.get("WAYLAND_DISPLAY") or env.get("QT_QPA_PLATFORM")):
        return NoWindow(f"No display (DISPLAY is not set): {headless_words(program)}", True)
    if importlib.util.find_spec("PySide6") is None:
        return NoWindow(f"PySide6 is not installed (pip install 'kame[gui]'): {headless_words(program)}", False)
    probe = run_command([sys.executable, "-m", "kame.turtlesim.gui"], env={**env, "QT_DEBUG_PLUGINS": "1"},
                        timeout=WINDOW_PROBE_SECONDS)
    verdict = window_verdict(probe.returncode, probe.output, platform.python_version(), program)
    return NoWindow(verdict, False) if verdict is not None else None
