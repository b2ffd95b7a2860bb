"""rostest's Python API, as test scripts use it: `rostest.rosrun(pkg, name, TestCaseClass)` and friends.

A rospy test node runs its unittest cases with `rosrun`; rostest started it with
`--gtest_output=xml:<file>`, where the JUnit results go (without it: ROS_HOME/test_results/<pkg>/
rosunit-<name>.xml). `--text` prints plain unittest output instead. On failure the process exits 1.
"""

from __future__ import annotations

import os
import sys
import unittest
import warnings
from collections.abc import Sequence
from typing import Any

from kame import environ, names
from kame.cli import _junit
from kame.net.xmlrpc_client import XmlRpcProxy

XML_OUTPUT_FLAG = _junit.XML_OUTPUT_FLAG
_GLOBAL_CALLER_ID = "/script"


def _master_uri() -> str:
    return environ.master_uri(os.environ, names.parse_args(sys.argv).special, default=environ.SETUP_MASTER_URI)


class MasterHandle:
    """What rostest's get_master gave (an xmlrpc.client.ServerProxy): `master.method(*args)` calls
    the master's `method` and returns its whole answer, over kame's XML-RPC client."""

    def __init__(self, uri: str) -> None:
        self._proxy = XmlRpcProxy(uri)

    def __getattr__(self, method: str) -> Any:
        if method.startswith("_"):
            raise AttributeError(method)

        def call(*args: object) -> Any:
            return self._proxy.call(method, *args)

        return call


def get_master() -> MasterHandle:
    """An XML-RPC handle to the master."""
    return MasterHandle(_master_uri())


def _system_state() -> list[list[list[Any]]]:
    reply: Any = get_master().getSystemState(_GLOBAL_CALLER_ID)
    code, msg, state = reply
    if code != 1:
        raise OSError(f"Unable to retrieve master state: {msg}")
    return list(state)


def is_subscriber(topic: str, subscriber_id: str) -> bool:
    """True if the master has `subscriber_id` subscribed to `topic`."""
    for name, nodes in _system_state()[1]:
        if name == topic:
            return subscriber_id in nodes
    return False


def is_publisher(topic: str, publisher_id: str) -> bool:
    """True if the master has `publisher_id` publishing `topic`."""
    for name, nodes in _system_state()[0]:
        if name == topic:
            return publisher_id in nodes
    return False


def _run_suite(package: str, test_name: str, test: object, sysargs: Sequence[str]) -> unittest.TestResult:
    args = list(sysargs)
    suite = _junit.load_suite(test)
    if "--text" in args:
        return unittest.TextTestRunner(verbosity=2).run(suite)
    return _junit.create_xml_runner(package, test_name, _junit.result_file_from_args(args)).run(suite)


def rosrun(package: str, test_name: str, test: object, sysargs: Sequence[str] | None = None) -> None:
    """Run a unittest-based integration test inside a rospy node (the node should be initialised).

    `test` is a TestCase class, a suite or case, or a dotted name. Exits 1 when a test failed.
    """
    result = _run_suite(package, test_name, test, sys.argv if sysargs is None else sysargs)
    print(_junit.unittest_summary(result), flush=True)
    import rospy

    rospy.signal_shutdown("test complete")
    if not result.wasSuccessful():
        sys.exit(1)


run = rosrun


def unitrun(package: str, test_name: str, test: object, sysargs: Sequence[str] | None = None,
            coverage_packages: Sequence[str] | None = None) -> None:
    """Run offline unittests (no ROS graph needed) with JUnit XML results. Exits 1 when a test failed.

    Deprecated in rostest: rosunit.unitrun, which it calls.
    """
    warnings.warn("Call to deprecated function unitrun.", category=DeprecationWarning, stacklevel=2)
    import rosunit

    rosunit.unitrun(package, test_name, test, sysargs=sysargs, coverage_packages=coverage_packages)


def rostestmain() -> None:
    from kame.cli.rostest import main

    sys.exit(main())


__all__ = ["XML_OUTPUT_FLAG", "get_master", "is_publisher", "is_subscriber", "rosrun", "rostestmain", "run",
           "unitrun"]
