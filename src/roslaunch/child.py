"""roslaunch.child: ROSLaunchChild, a roslaunch child as ROS runs one: a process monitor, a
ROSLaunchChildNode registered with the parent's server, and nodes run when the parent calls
`launch`. It runs until its processes end or it is shut down (main thread: it takes the signals,
as ROS's does). kame's own `roslaunch -c` child is kame.launch.remote's, fed over SSH.
"""

from __future__ import annotations

import logging
import traceback

from roslaunch import core, pmon, server
from roslaunch.nodeprocess import DEFAULT_TIMEOUT_SIGINT, DEFAULT_TIMEOUT_SIGTERM

__all__ = ["DEFAULT_TIMEOUT_SIGINT", "DEFAULT_TIMEOUT_SIGTERM", "ROSLaunchChild"]


class ROSLaunchChild:
    def __init__(self, run_id: str, name: str, server_uri: str, sigint_timeout: float = DEFAULT_TIMEOUT_SIGINT,
                 sigterm_timeout: float = DEFAULT_TIMEOUT_SIGTERM) -> None:
        core.set_child_mode(True)
        self.logger = logging.getLogger("roslaunch.child")
        self.run_id = run_id
        self.name = name
        self.server_uri = server_uri
        self.child_server: server.ROSLaunchChildNode | None = None
        self.pm: pmon.ProcessMonitor | None = None
        self.sigint_timeout = sigint_timeout
        self.sigterm_timeout = sigterm_timeout
        pmon._init_signal_handlers()

    def _start_pm(self) -> None:
        if self.pm is None:
            self.pm = pmon.start_process_monitor()
        if self.pm is None:
            raise core.RLException("cannot startup remote child: unable to start process monitor.")

    def run(self) -> None:
        """Serve and run what the parent sends, until the child's processes end or shutdown()."""
        try:
            self._start_pm()
            assert self.pm is not None
            self.child_server = server.ROSLaunchChildNode(self.run_id, self.name, self.server_uri, self.pm,
                                                          sigint_timeout=self.sigint_timeout,
                                                          sigterm_timeout=self.sigterm_timeout)
            self.child_server.start()
            self.pm.mainthread_spin()
        except Exception:
            self.logger.error(traceback.format_exc())
            raise
        finally:
            self.shutdown()
            if self.child_server is not None:
                self.child_server.shutdown("roslaunch child complete")

    def shutdown(self) -> None:
        if self.pm is not None:
            self.pm.shutdown()
            self.pm.join()
