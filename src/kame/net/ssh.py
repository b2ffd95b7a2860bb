"""One command run on another machine over SSH (paramiko): what roslaunch's `<machine>` nodes ride on.

Rules (roslaunch's remoteprocess, with its wording):
- The user's ~/.ssh/config may rename the host (HostName), give the user (User) and the key
  (IdentityFile). Without a password, the keys of ~/.ssh and the SSH agent are offered.
- The host must already be in ~/.ssh/known_hosts (or /etc/ssh/ssh_known_hosts): an unknown host
  is refused, naming the `ssh` command that would add it, unless ROSLAUNCH_SSH_UNKNOWN=1, when it
  is accepted (and remembered for this connection only). roslaunch looks a host up by its bare
  name whatever the port; we look it up as ssh does, `[host]:port` for a port other than 22.
- Connecting gives up after 30 s (roslaunch's TIMEOUT_SSH_CONNECT). Failures are `SshError`s
  whose text is roslaunch's.
- The command's stdout and stderr are read line by line by two threads the `RemoteCommand`
  owns; `close()` ends the connection and joins them. Closing the command's stdin is how the
  remote side learns it is to stop (an SSH session without a terminal gets no SIGHUP).

paramiko is imported when a connection is made: roslaunch without remote machines does not pay
for loading it (and its cryptography) at every start.
"""

from __future__ import annotations

import logging
import os
import threading
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import IO, TYPE_CHECKING, Any

if TYPE_CHECKING:
    import paramiko

log = logging.getLogger("kame.net.ssh")

SSH_CONNECT_TIMEOUT = 30.0
LOST = -1  # the exit status of a command whose channel closed without one (paramiko's): the connection was lost
SYSTEM_KNOWN_HOSTS = "/etc/ssh/ssh_known_hosts"


class SshError(Exception):
    """A connection or command that could not be made; the text is what roslaunch says."""


@dataclass(frozen=True)
class SshTarget:
    address: str
    port: int = 22
    user: str | None = None
    password: str | None = None


def _user_config(address: str) -> dict[str, Any]:
    """The ~/.ssh/config block for `address` (hostname, user, identityfile), empty when there is none."""
    import paramiko

    path = os.path.join(os.path.expanduser("~"), ".ssh", "config")
    try:
        with open(path) as f:
            config = paramiko.SSHConfig()
            config.parse(f)
    except OSError:
        return {}
    return dict(config.lookup(address))


def known_hosts_key(address: str, port: int) -> str:
    """How known_hosts names a host: `host`, or `[host]:port` for a port other than 22."""
    return address if port == 22 else f"[{address}]:{port}"


def known_hosts_problem(client: paramiko.SSHClient, address: str, port: int, user: str | None,
                        env: Mapping[str, str]) -> str | None:
    """roslaunch's ssh_check_known_hosts: None when `address` may be connected to, else what to do."""
    import paramiko

    try:
        if os.path.isfile(SYSTEM_KNOWN_HOSTS):
            client.load_system_host_keys(SYSTEM_KNOWN_HOSTS)
        client.load_system_host_keys()  # ~/.ssh/known_hosts
    except (OSError, paramiko.SSHException, ValueError) as exc:
        log.error("cannot load SSH host keys: %s", exc)
        return "cannot load SSH host keys -- your known_hosts file may be corrupt"
    if env.get("ROSLAUNCH_SSH_UNKNOWN") == "1":
        client.set_missing_host_key_policy(paramiko.AutoAddPolicy())
        return None
    # what load_system_host_keys loaded (get_host_keys() holds only load_host_keys'): no public accessor
    if client._system_host_keys.lookup(known_hosts_key(address, port)) is not None:
        return None
    port_str = f"-p {port} " if port != 22 else ""
    user_str = f"{user}@" if user else ""
    return (f"{address} is not in your SSH known_hosts file.\n\n"
            f"Please manually:\n  ssh {port_str}{user_str}{address}\n\n"
            "then try roslaunching again.\n\n"
            "If you wish to configure roslaunch to automatically recognize unknown\n"
            "hosts, please set the environment variable ROSLAUNCH_SSH_UNKNOWN=1")


def connect(target: SshTarget, env: Mapping[str, str] | None = None,
            timeout: float = SSH_CONNECT_TIMEOUT) -> paramiko.SSHClient:
    """A connected client, or SshError in roslaunch's words."""
    try:
        import paramiko
    except ImportError:
        raise SshError("paramiko is not installed") from None
    env = os.environ if env is None else env
    config = _user_config(target.address)
    address = config.get("hostname") or target.address
    user = target.user or config.get("user")
    identity = config.get("identityfile")
    key_files = [os.path.expanduser(f) for f in identity] if isinstance(identity, list) else (
        [os.path.expanduser(identity)] if identity else None)
    client = paramiko.SSHClient()
    problem = known_hosts_problem(client, address, target.port, user, env)
    if problem is not None:
        client.close()
        raise SshError(problem)
    user_str = f"{user}@" if user else ""
    try:
        if target.password is None:  # keys: ~/.ssh's, the agent's, the config's IdentityFile
            client.connect(address, target.port, user, timeout=timeout, key_filename=key_files)
        else:
            client.connect(address, target.port, user, target.password, timeout=timeout,
                           allow_agent=False, look_for_keys=False)
        return client
    except paramiko.BadHostKeyException:
        message = f"Unable to verify host key for remote computer[{address}:{target.port}]"
    except paramiko.AuthenticationException:
        message = (f"Authentication to remote computer[{user_str}{address}:{target.port}] failed.\n"
                   "A common cause of this error is a missing key in your authorized_keys file.")
    except paramiko.SSHException as exc:
        message = f"Unable to establish ssh connection to [{user_str}{address}:{target.port}]: {exc}"
    except ConnectionRefusedError:
        message = f"network connection refused by [{address}:{target.port}]"
    except OSError as exc:  # a timeout too
        message = f"network error connecting to [{address}:{target.port}]: {exc}"
    client.close()
    log.error("ssh to %s:%s: %s", address, target.port, message)
    raise SshError(message)


class RemoteCommand:
    """`command` running on `target`: stdin to write to, each stdout/stderr line handed to a callback.

    The callbacks run on the command's reader threads; `on_end` runs once both streams have ended.
    """

    def __init__(self, target: SshTarget, command: str, on_stdout: Callable[[str], None],
                 on_stderr: Callable[[str], None], on_end: Callable[[], None] = lambda: None,
                 env: Mapping[str, str] | None = None, connect_timeout: float = SSH_CONNECT_TIMEOUT) -> None:
        self.client = connect(target, env, connect_timeout)
        import paramiko

        try:
            transport = self.client.get_transport()
            assert transport is not None  # connected
            channel = transport.open_session()
            channel.exec_command(command)
        except (paramiko.SSHException, OSError, EOFError) as exc:
            self.client.close()
            raise SshError(f"Unable to run [{command}] on [{target.address}:{target.port}]: {exc}") from exc
        # binary files: the remote side's bytes are decoded here, a bad byte replaced, never an exception
        stdin, stdout, stderr = channel.makefile_stdin("wb"), channel.makefile("rb"), channel.makefile_stderr("rb")
        self._stdin = stdin
        self._channel = channel
        self._on_end = on_end
        self._pending = 2
        self._lock = threading.Lock()
        self._threads = [threading.Thread(target=self._pump, args=(stream, callback), daemon=True,
                                          name=f"ssh-{target.address}-{which}")
                         for stream, callback, which in ((stdout, on_stdout, "out"), (stderr, on_stderr, "err"))]
        for thread in self._threads:
            thread.start()

    def _pump(self, stream: IO[bytes], callback: Callable[[str], None]) -> None:
        try:
            for raw in stream:
                callback(raw.decode("utf-8", "replace").rstrip("\r\n"))
        except (OSError, EOFError) as exc:  # the connection lost: the stream has ended
            log.info("ssh stream ended: %s", exc)
        finally:
            with self._lock:
                self._pending -= 1
                last = self._pending == 0
            if last:
                self._on_end()

    def write(self, data: bytes) -> None:
        self._stdin.write(data)
        self._stdin.flush()

    def close_stdin(self) -> None:
        """End of input for the remote command: its sign to stop."""
        try:
            self._channel.shutdown_write()
        except (OSError, EOFError) as exc:
            log.info("ssh stdin already closed: %s", exc)

    def wait(self, timeout: float) -> int | None:
        """The command's exit status (LOST when the connection ended without one), or None when it
        has not ended within `timeout`."""
        if not self._channel.status_event.wait(timeout):
            return None
        return int(self._channel.recv_exit_status())

    def close(self) -> None:
        """The connection closed and the reader threads joined."""
        self.client.close()
        for thread in self._threads:
            if thread is not threading.current_thread():
                thread.join()
