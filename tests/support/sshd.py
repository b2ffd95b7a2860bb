"""A real OpenSSH server on one test host (a network namespace of tests/support/netns.py).

`Sshd` makes, in a folder of its own: a host key, a configuration (its port, keys only for
root, no PAM, its own PID and authorized_keys files), and for the client a key pair in
`<home>/.ssh` with a known_hosts file naming the server. The server runs in the foreground
as our child (`sshd -D -e`), and `close()` stops it by its PID. Nothing outside `home` is
touched but /run/sshd, the privilege separation folder sshd insists on.

It needs root and openssh-server: `Sshd.unavailable()` says why not, for a skip.
"""

from __future__ import annotations

import os
import shutil
import subprocess
from pathlib import Path

from . import Proc
from .netns import Host

SSHD = Path("/usr/sbin/sshd")
PRIVSEP_DIR = Path("/run/sshd")


def _keygen(path: Path) -> str:
    """A new ed25519 key pair at `path` (and `path`.pub); the public line."""
    subprocess.run(["ssh-keygen", "-q", "-t", "ed25519", "-N", "", "-C", "kame-test", "-f", str(path)], check=True,
                   capture_output=True)
    return path.with_suffix(".pub").read_text().strip()


class Sshd:
    def __init__(self, host: Host, home: Path, port: int = 2222, env: dict[str, str] | None = None) -> None:
        self.host = host
        self.port = port
        self.home = home  # the client's HOME: .ssh/id_ed25519 and .ssh/known_hosts
        folder = home / "sshd"
        folder.mkdir(parents=True)
        host_key = folder / "host_ed25519"
        host_public = _keygen(host_key)
        ssh_dir = home / ".ssh"
        ssh_dir.mkdir(mode=0o700)
        (folder / "authorized_keys").write_text(_keygen(ssh_dir / "id_ed25519") + "\n")  # the key clients look for
        self.known_hosts_line = f"[{host.name}]:{port} {' '.join(host_public.split()[:2])}\n"
        (ssh_dir / "known_hosts").write_text(self.known_hosts_line)
        config = folder / "sshd_config"
        config.write_text("\n".join([
            f"Port {port}", f"ListenAddress {host.address}", f"HostKey {host_key}", f"PidFile {folder / 'sshd.pid'}",
            f"AuthorizedKeysFile {folder / 'authorized_keys'}", "PermitRootLogin prohibit-password",
            "PasswordAuthentication yes", "KbdInteractiveAuthentication no", "UsePAM no", "StrictModes no",
            "UseDNS no", "LogLevel VERBOSE", "",
        ]))
        PRIVSEP_DIR.mkdir(mode=0o755, exist_ok=True)
        self.proc = Proc(host.command([str(SSHD), "-D", "-e", "-f", str(config)]), env or dict(os.environ))
        try:
            self._wait_listening()
        except BaseException:
            self.close()
            raise

    def _wait_listening(self) -> None:
        import time

        deadline = time.monotonic() + 15
        while not any(f"Server listening on {self.host.address} port {self.port}" in line for line in self.proc.err):
            if self.proc.popen.poll() is not None or time.monotonic() > deadline:
                raise AssertionError(f"sshd did not start: {''.join(self.proc.err)}")
            time.sleep(0.02)

    @staticmethod
    def unavailable() -> str | None:
        if os.geteuid() != 0:
            return "sshd in a network namespace needs root"
        if not SSHD.exists() or shutil.which("ssh-keygen") is None:
            return "openssh-server is not installed (scripts/install-ros-peers.sh installs it)"
        return None

    def sessions(self) -> list[int]:
        """The PIDs of every process below sshd (its sessions and what they run): none once all ended."""
        found, todo = [], children(self.proc.pid)
        while todo:
            pid = todo.pop()
            found.append(pid)
            todo.extend(children(pid))
        return found

    def close(self) -> str:
        """sshd stopped (SIGINT, then SIGKILL: Proc.stop); its log."""
        _, err = self.proc.stop()
        return err


def children(pid: int) -> list[int]:
    """The PIDs of the processes `pid` started that are still running."""
    try:
        text = Path(f"/proc/{pid}/task/{pid}/children").read_text()
    except OSError:
        return []
    return [int(p) for p in text.split()]
