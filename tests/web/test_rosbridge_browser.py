"""A web page on roslibjs in headless Chromium, through kame's rosbridge: it subscribes to
/turtle1/pose, drives /turtle1/cmd_vel, calls /spawn, reads a parameter, serves a service that a
kame rospy node calls, and shows what Debian's rospy publishes. The test serves the page (and
roslib from tests/web/node_modules) over HTTP, drives Chromium through its DevTools protocol,
reads the page's DOM and saves its screenshot in the tour (build/tour/rosbridge_browser.png)."""

from __future__ import annotations

import base64
import functools
import http.server
import itertools
import json
import shutil
import subprocess
import sys
import textwrap
import threading
import urllib.request
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import pytest
from websockets.sync.client import connect

from tests.support import SYSTEM_PYTHON, Proc, free_port, have_debian_ros, wait_until
from tests.support.tour import tour_dir
from tests.web.rosbridge_graph import WEB, bridge_graph, have_node_roslib

CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")

pytestmark = [pytest.mark.timeout(240),
              pytest.mark.skipif(CHROMIUM is None or not have_node_roslib(),
                                 reason="chromium or tests/web/node_modules missing (scripts/install-web-peers.sh)")]


class _Quiet(http.server.SimpleHTTPRequestHandler):
    # a module script must come as JavaScript, which the system's MIME table may not say of .mjs
    extensions_map = {**http.server.SimpleHTTPRequestHandler.extensions_map, ".mjs": "text/javascript",
                      ".js": "text/javascript"}

    def log_message(self, format: str, *args: Any) -> None:
        pass


@contextmanager
def page_server() -> Iterator[int]:
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), functools.partial(_Quiet, directory=str(WEB)))
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    try:
        yield server.server_address[1]
    finally:
        server.shutdown()
        server.server_close()
        thread.join()


class DevTools:
    """Chromium's DevTools protocol over the websockets client: one page, commands in turn."""

    def __init__(self, ws: Any) -> None:
        self.ws = ws
        self._ids = itertools.count(1)

    def call(self, method: str, timeout: float = 60.0, **params: Any) -> dict[str, Any]:
        call_id = next(self._ids)
        self.ws.send(json.dumps({"id": call_id, "method": method, "params": params}))
        while True:
            answer = json.loads(self.ws.recv(timeout=timeout))
            if answer.get("id") == call_id:
                if "error" in answer:
                    raise AssertionError(f"{method}: {answer['error']}")
                return dict(answer["result"])

    def when(self, mark: str, timeout: float = 60.0) -> str:
        """The page's text for `mark`, once the page has it (its window.pageMark promise)."""
        return str(self.evaluate(f"window.pageMark({json.dumps(mark)})", timeout))

    def evaluate(self, expression: str, timeout: float = 60.0) -> Any:
        result = self.call("Runtime.evaluate", timeout=timeout, expression=expression, awaitPromise=True,
                           returnByValue=True)
        if "exceptionDetails" in result:
            raise AssertionError(f"{expression}: {result['exceptionDetails']}")
        return result["result"].get("value")

    def text(self, element: str) -> str:
        return str(self.evaluate(f"document.getElementById({json.dumps(element)}).textContent"))


@contextmanager
def chromium(url: str, profile: Path) -> Iterator[DevTools]:
    assert CHROMIUM is not None
    port = free_port()
    proc = Proc([CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
                 f"--remote-debugging-port={port}", "--remote-debugging-address=127.0.0.1",
                 f"--user-data-dir={profile}", "--window-size=900,760", url], {"HOME": str(profile),
                                                                                  "PATH": "/usr/bin:/bin"})
    try:
        pages: list[dict[str, Any]] = []

        def page_listed() -> bool:
            try:
                with urllib.request.urlopen(f"http://127.0.0.1:{port}/json/list", timeout=2) as answer:
                    pages[:] = [p for p in json.load(answer) if p.get("type") == "page"]
            except OSError:
                return False
            return bool(pages)

        assert wait_until(page_listed, 60), f"no DevTools page:\n{''.join(proc.err)[-2000:]}"
        with connect(pages[0]["webSocketDebuggerUrl"], max_size=None, open_timeout=20) as ws:
            devtools = DevTools(ws)
            # the page's module script defines window.pageMark once roslib and its imports are loaded
            assert wait_until(lambda: devtools.evaluate("typeof window.pageMark") == "function", 60), \
                devtools.evaluate("import('roslib').then(() => 'roslib loaded', (error) => String(error))")
            yield devtools
    finally:
        proc.stop()


def test_a_page_on_roslibjs_drives_turtlesim(tmp_path: Path) -> None:
    with bridge_graph(tmp_path / "ros") as graph, page_server() as http_port:
        talker = None
        if have_debian_ros():
            script = tmp_path / "talker.py"
            script.write_text(textwrap.dedent("""
                import rospy
                from std_msgs.msg import String
                rospy.init_node("debian_talker")
                pub = rospy.Publisher("/chatter", String, queue_size=10)
                rate = rospy.Rate(10)
                while not rospy.is_shutdown():
                    pub.publish(String("hello from Debian's rospy"))
                    rate.sleep()
            """))
            talker = Proc([SYSTEM_PYTHON, str(script)], graph.env)
        try:
            url = f"http://127.0.0.1:{http_port}/rosbridge_page.html?ws={graph.url}"
            with chromium(url, tmp_path / "chromium") as page:
                assert page.when("connection") == f"connected to {graph.url}"
                assert page.when("pose").startswith("x=5.544 y=5.544")
                assert page.when("moved").startswith("x 5.544 -> ")
                assert page.when("spawn") == "spawned browser_turtle"
                assert page.when("param") == "69"
                caller = textwrap.dedent("""
                    import rospy
                    from rospy_tutorials.srv import AddTwoInts
                    rospy.init_node("browser_caller")
                    rospy.wait_for_service("/browser_add", timeout=30)
                    print("sum", rospy.ServiceProxy("/browser_add", AddTwoInts)(19, 23).sum, flush=True)
                """)
                done = subprocess.run([sys.executable, "-c", caller], env=graph.env, capture_output=True, text=True,
                                      timeout=60)
                assert done.stdout.strip() == "sum 42", done.stderr
                assert page.when("service") == "called with a=19 b=23, answered 42"
                if talker is not None:
                    assert page.when("chatter") == "hello from Debian's rospy"
                assert page.text("errors") == ""
                shot = page.call("Page.captureScreenshot", format="png")
                path = tour_dir() / "rosbridge_browser.png"
                path.write_bytes(base64.b64decode(shot["data"]))
                assert path.stat().st_size > 10_000
        finally:
            if talker is not None:
                talker.stop()
