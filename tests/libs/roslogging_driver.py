"""rosgraph.roslogging.configure_logging in a fresh ROS_LOG_DIR: where it logs, the `latest`
link, and a logged line's shape; prints JSON. Run by kame's interpreter and Debian's."""

from __future__ import annotations

import json
import logging
import os
import re
import sys

import rosgraph.roslogging

log_dir = sys.argv[1]
first = rosgraph.roslogging.configure_logging("probe")
second = rosgraph.roslogging.configure_logging("probe", filename=os.path.join("run1", "probe-x.log"))
logging.getLogger("probe.child").info("hello %s", "log")
logging.getLogger("probe.child").debug("not at INFO")
for handler in logging.getLogger().handlers:
    handler.flush()
pid = str(os.getpid())
lines = [re.sub(r"\d{4}-\d\d-\d\d \d\d:\d\d:\d\d,\d+", "TIME", line) for line in open(second).read().splitlines()]
blocked = os.path.join(log_dir, "blocked")
open(blocked, "w").close()
try:
    rosgraph.roslogging.configure_logging("probe", filename=os.path.join("blocked", "x.log"))
    error = None
except rosgraph.roslogging.LoggingException as exc:
    error = str(exc).replace(log_dir, "LOG")
print(json.dumps({"first": first.replace(log_dir, "LOG").replace(pid, "PID"),
                  "second": second.replace(log_dir, "LOG"),
                  "latest": os.readlink(os.path.join(log_dir, "latest")).replace(log_dir, "LOG"),
                  "lines": [line for line in lines if "probe.child" in line], "error": error}))
