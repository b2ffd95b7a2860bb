"""A dynamic_reconfigure client program, run by kame's interpreter or Debian's (real rospy and client).

argv: the server's name, then JSON changes to send one after another. Prints one JSON line:
the parameter names described, the first configuration, each answer to update_configuration,
the configuration the config_callback saw last, the servers the package finds, and what an
unknown parameter raises (upstream's exception classes, importable from the package itself).
"""

import json
import sys
import threading

import dynamic_reconfigure
import rospy
from dynamic_reconfigure.client import Client

seen = []
changed = threading.Condition()


def on_config(config):
    with changed:
        seen.append(config)
        changed.notify_all()


def unknown_parameter(client):
    try:
        client.update_configuration({"no_such_param": 1})
    except dynamic_reconfigure.DynamicReconfigureException as exc:
        return [type(exc).__name__, str(exc),
                isinstance(exc, dynamic_reconfigure.DynamicReconfigureParameterException)]
    return None


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
                      "groups": sorted(client.get_configuration()["groups"]["groups"]),
                      "services": dynamic_reconfigure.find_reconfigure_services(),
                      "unknown": unknown_parameter(client),
                      "callback_error": issubclass(dynamic_reconfigure.DynamicReconfigureCallbackException,
                                                   dynamic_reconfigure.DynamicReconfigureException)}))
    client.close()
