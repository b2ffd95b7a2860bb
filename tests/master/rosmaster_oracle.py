"""Runs a list of master calls through Debian's real rosmaster handler (no sockets).

Used by the differential tests: reads JSON [[method, params], ...] on stdin and prints JSON
[[result, notifications], ...], where notifications are what rosmaster queued for its thread
pool, as [method, node_api, *args]. Runs under /usr/bin/python3 with rosmaster importable.
"""

import json
import sys

import rosmaster.master_api as api


class Recorder:
    def __init__(self):
        self.queued = []

    def queue_task(self, _key, task, args):
        name = getattr(task, "__name__", "")
        if name == "publisher_update_task":
            node_api, topic, uris = args
            self.queued.append(["publisherUpdate", node_api, topic, list(uris)])
        elif name == "param_update_task":
            _caller_id, node_api, key, value = args
            self.queued.append(["paramUpdate", node_api, key, value])
        elif name == "shutdown_node_task":
            node_api, caller_id, reason = args
            self.queued.append(["shutdown", node_api, f"[{caller_id}] Reason: {reason}"])
        else:
            raise AssertionError(name)

    def join_all(self, **_kw):
        pass


def main():
    handler = api.ROSMasterHandler()
    handler.thread_pool = handler.reg_manager.thread_pool = rec = Recorder()
    handler._ready("http://127.0.0.1:11311/")
    out = []
    for method, params in json.loads(sys.stdin.read()):
        rec.queued = []
        if method.startswith("_") or not hasattr(handler, method):
            result = ["fault", 1, f'<class \'Exception\'>:method "{method}" is not supported']
        else:
            result = getattr(handler, method)(*params)
        out.append(json.dumps([result, rec.queued]))  # now: results may be live parts of the tree
    print("[" + ", ".join(out) + "]")


main()
