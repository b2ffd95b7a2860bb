"""dynamic_reconfigure's messages against Debian's python3-dynamic-reconfigure: md5sums and definitions."""

from __future__ import annotations

import importlib
import json
import subprocess
from pathlib import Path

import pytest

SYSTEM_PYTHON = Path("/usr/bin/python3")
MSGS = ["BoolParameter", "Config", "ConfigDescription", "DoubleParameter", "Group", "GroupState",
        "IntParameter", "ParamDescription", "SensorLevels", "StrParameter"]
SRVS = ["Reconfigure", "ReconfigureRequest", "ReconfigureResponse"]

ASK_DEBIAN = f"""
import json, dynamic_reconfigure.msg as m, dynamic_reconfigure.srv as s
out = {{}}
for n in {MSGS!r}:
    c = getattr(m, n); out[n] = [c._type, c._md5sum, c._full_text]
for n in {SRVS!r}:
    c = getattr(s, n); out[n] = [c._type, c._md5sum, getattr(c, "_full_text", "")]
print(json.dumps(out))
"""


def debian_answer() -> dict[str, list[str]] | None:
    if not SYSTEM_PYTHON.exists():
        return None
    result = subprocess.run([str(SYSTEM_PYTHON), "-c", ASK_DEBIAN], capture_output=True, text=True, timeout=60)
    if result.returncode != 0:
        return None
    answer: dict[str, list[str]] = json.loads(result.stdout)
    return answer


DEBIAN = debian_answer()


@pytest.mark.skipif(DEBIAN is None, reason="Debian's python3-dynamic-reconfigure is not installed")
@pytest.mark.parametrize("name", MSGS + SRVS)
def test_type_md5sum_and_definition_equal_debians(name: str) -> None:
    assert DEBIAN is not None
    kind = "srv" if name in SRVS else "msg"
    cls = getattr(importlib.import_module(f"dynamic_reconfigure.{kind}"), name)
    assert [cls._type, cls._md5sum, getattr(cls, "_full_text", "")] == DEBIAN[name]


def test_sensor_levels_constants() -> None:
    from dynamic_reconfigure.msg import SensorLevels

    levels = (SensorLevels.RECONFIGURE_RUNNING, SensorLevels.RECONFIGURE_STOP, SensorLevels.RECONFIGURE_CLOSE)
    assert levels == (0, 1, 3)


def test_a_service_call_takes_the_message_of_the_requests_one_field() -> None:
    # Debian's Client calls set_parameters(config): rospy builds ReconfigureRequest(config) from it
    from dynamic_reconfigure.msg import Config, Group, IntParameter
    from dynamic_reconfigure.srv import ReconfigureRequest
    from kame.client.message_args import args_kwds_to_message

    config = Config(ints=[IntParameter("x", 3)])
    assert args_kwds_to_message(ReconfigureRequest, (config,), {}) == ReconfigureRequest(config)
    with pytest.raises(TypeError, match=r"expected \[dynamic_reconfigure/Config\] but got \[dynamic_reconfigure/Group"):
        args_kwds_to_message(ReconfigureRequest, (Group(),), {})
    request = ReconfigureRequest(config)  # the request itself, one field or not, is taken as it is (rospy's md5 rule)
    assert args_kwds_to_message(ReconfigureRequest, (request,), {}) is request
