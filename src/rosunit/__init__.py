"""rosunit's Python API, as unit test scripts use it: `rosunit.unitrun(pkg, name, TestCaseClass)`.

Offline unittests (no ROS graph) with JUnit XML results in ROS_HOME/test_results/<pkg>/
rosunit-<name>.xml, or where `--gtest_output=xml:<file>` says; `--text` prints plain unittest output.
"""

from __future__ import annotations

import sys
import unittest
from collections.abc import Sequence

from kame.cli._junit import (
    XML_OUTPUT_FLAG,
    create_xml_runner,
    load_suite,
    result_file_from_args,
    rostest_name_from_path,
    unittest_summary,
    xml_results_file,
)


def print_unittest_summary(result: unittest.TestResult) -> None:
    print(unittest_summary(result), flush=True)


def unitrun(package: str, test_name: str, test: object, sysargs: Sequence[str] | None = None,
            coverage_packages: Sequence[str] | None = None) -> None:
    """Run `test` (a TestCase class, suite or dotted name) with XML results; exits 1 when a test failed.

    Coverage options (`--cov`, `coverage_packages`) are accepted and ignored.
    """
    args = list(sys.argv if sysargs is None else sysargs)
    suite = load_suite(test)
    if "--text" in args:
        result: unittest.TestResult = unittest.TextTestRunner(verbosity=2).run(suite)
    else:
        result = create_xml_runner(package, test_name, result_file_from_args(args)).run(suite)
    print_unittest_summary(result)
    if not result.wasSuccessful():
        sys.exit(1)


__all__ = ["XML_OUTPUT_FLAG", "create_xml_runner", "print_unittest_summary", "rostest_name_from_path", "unitrun",
           "xml_results_file"]
