"""A dynamic_reconfigure client program, run by kame's interpreter or Debian's (real rospy and client).

argv: the server's name, then JSON changes to send one after another. Prints one JSON line:
the parameter names described, the first configuration, each answer to update_configuration,
and the configuration the config_callback saw last.
"""

import json
import sys
import threading

import rospy
from dynamic_reconfigure.client import Client

seen = []
changed = threading.Condition()


def on_config(config):
    with changed:
        seen.append(config)
        changed.notify_all()


def plain(config):
    return {k: v for k, v in config.items() if k != "groups"}


if __name__ == "__main__":
    rospy.init_node("client_driver")
    client = Client(sys.argv[1], timeout=30, config_callback=on_config)
    descriptions = client.get_parameter_descriptions()
    first = plain(client.get_configuration())
    answers = [plain(client.update_configuration(json.loads(change))) for change in sys.argv[2:]]
    with changed:
        changed.wait_for(lambda: seen and plain(seen[-1]) == answers[-1], timeout=30)
    print(json.dumps({"names": [d["name"] for d in descriptions], "types": [d["type"] for d in descriptions],
                      "first": first, "answers": answers, "last_seen": plain(seen[-1]),
                      "groups": sorted(client.get_configuration()["groups"]["groups"])}))
    client.close()
