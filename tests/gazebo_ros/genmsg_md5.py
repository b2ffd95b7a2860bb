"""Run by Debian's /usr/bin/python3: genmsg's md5sums of every gazebo_msgs definition kame ships.

    /usr/bin/python3 genmsg_md5.py SHARE_DIR  ->  JSON {"gazebo_msgs/ModelStates": md5, ...}

Its dependencies (std_msgs, geometry_msgs, sensor_msgs, trajectory_msgs) come from Debian's
/usr/share, as a catkin build of gazebo_msgs would find them.
"""

import json
import os
import sys

import genmsg
import genmsg.msg_loader

share = sys.argv[1]
package = "gazebo_msgs"
search = {package: [os.path.join(share, package, "msg")]}
for dep in ("std_msgs", "geometry_msgs", "sensor_msgs", "trajectory_msgs"):
    search[dep] = [os.path.join("/usr/share", dep, "msg")]
context = genmsg.msg_loader.MsgContext.create_default()
sums = {}
for kind in ("msg", "srv"):
    folder = os.path.join(share, package, kind)
    for name in sorted(os.listdir(folder)):
        base = name[:-len(kind) - 1]
        full = f"{package}/{base}"
        path = os.path.join(folder, name)
        if kind == "msg":
            spec = genmsg.msg_loader.load_msg_from_file(context, path, full)
            genmsg.msg_loader.load_depends(context, spec, search)
            sums[full] = genmsg.compute_md5(context, spec)
        else:
            spec = genmsg.msg_loader.load_srv_from_file(context, path, full)
            genmsg.msg_loader.load_depends(context, spec, search)
            sums[full] = genmsg.compute_md5(context, spec)
            sums[full + "Request"] = genmsg.compute_md5(context, spec.request)
            sums[full + "Response"] = genmsg.compute_md5(context, spec.response)
print(json.dumps(sums))
