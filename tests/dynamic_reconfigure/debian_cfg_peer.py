"""Run by Debian's /usr/bin/python3: evaluates a .cfg with catkin's parameter_generator_catkin.

argv[1]: the .cfg file. stdout: JSON {"description": the tree generatepy writes into the
Config module (infinities replaced), "constants": {"<Name>_<const>": value}}.
"""

import json
import sys

cfg = sys.argv[1]
sys.argv = [cfg, "unused", "unused", "unused", "unused"]  # the generator insists on catkin's arguments

from dynamic_reconfigure import parameter_generator_catkin  # noqa: E402


def dump(self, pkgname, nodename, name):
    constants = {name + "_" + c["name"]: c["value"] for c in self.constants}
    print(json.dumps({"description": self.replace_infinity(self.group.to_dict()), "constants": constants}))
    return 0


parameter_generator_catkin.ParameterGenerator.generate = dump
with open(cfg) as source:
    code = compile(source.read(), cfg, "exec")
try:
    exec(code, {"__name__": "__main__", "__file__": cfg})
except SystemExit as stop:
    sys.exit(stop.code)
