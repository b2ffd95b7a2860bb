"""The window tests' X server: a program connecting while the tests' own probes come and go is
never refused (an X server resets when its last client leaves, refusing whoever connects
meanwhile, unless started with -noreset)."""

from __future__ import annotations

import os
import subprocess

from .xserver import xvfb


def test_a_client_connecting_while_another_leaves_is_never_refused() -> None:
    with xvfb() as display:
        env = dict(os.environ, DISPLAY=display)
        refusals = []
        for _ in range(150):
            leaving = subprocess.Popen(["xwininfo", "-root"], env=env, stdout=subprocess.DEVNULL,
                                       stderr=subprocess.DEVNULL)
            arriving = subprocess.run(["xwininfo", "-root"], env=env, capture_output=True, text=True, timeout=10)
            if arriving.returncode != 0:
                refusals.append(arriving.stderr)
            leaving.wait(10)
        assert not refusals, f"{len(refusals)} of 150 connections refused, the first saying: {refusals[0]}"
