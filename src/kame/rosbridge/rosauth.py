"""rosauth's ros_mac_authentication: the /authenticate service that rosbridge asks (rosauth 1.0.x).

`rosrun rosauth ros_mac_authentication _secret_file_location:=FILE`. The file's first line is
the secret, exactly 16 characters long (rosauth's SECRET_LENGTH); the secret itself never goes
on the parameter server. A request is authenticated iff its time `t` is less than
~allowed_time_delta seconds (default 5; negative: no time check at all) from now, either way, its
`end` is after now, and its `mac` is the lowercase hex SHA-512 of secret + client + dest + rand +
t.secs + level + end.secs (the seconds in decimal, nanoseconds left out), as rosauth's C++ does.
Exit codes as rosauth's: -1 (255) without the parameter, -2 (254) for an unreadable file,
-3 (253) for a secret of the wrong length.
"""

from __future__ import annotations

import hashlib
import hmac
import sys
from collections.abc import Sequence
from typing import Any

from kame.client import log
from kame.client.clock import get_rostime
from kame.client.process import get_param, init_node, spin
from kame.client.services import Service
from kame.rostime import Time
from rosauth.srv import Authentication, AuthenticationResponse

SECRET_LENGTH = 16
DEFAULT_ALLOWED_TIME_DELTA = 5.0
MISSING_PARAMETER, FILE_IO_ERROR, INVALID_SECRET = -1, -2, -3


def mac(secret: str, client: str, dest: str, rand: str, t_secs: int, level: str, end_secs: int) -> str:
    """The MAC a client sends for these fields, as rosauth computes it."""
    text = f"{secret}{client}{dest}{rand}{t_secs}{level}{end_secs}"
    return hashlib.sha512(text.encode()).hexdigest()


def in_time(t: Time, end: Time, now: Time, allowed_time_delta: float) -> bool:
    """rosauth's time check: |t - now| in whole seconds under the delta, and `end` still ahead."""
    if allowed_time_delta < 0:
        return True
    return abs(t - now).secs < allowed_time_delta and end > now


def authenticated(secret: str, request: Any, now: Time, allowed_time_delta: float) -> bool:
    if not in_time(request.t, request.end, now, allowed_time_delta):
        return False
    expected = mac(secret, request.client, request.dest, request.rand, request.t.secs, request.level,
                   request.end.secs)
    return hmac.compare_digest(expected, request.mac)


def read_secret(path: str) -> str:
    """The file's first line without its line end (rosauth reads it with getline)."""
    with open(path, encoding="utf-8") as f:
        return f.readline().rstrip("\n")


def main(argv: Sequence[str] | None = None) -> int:
    init_node("ros_mac_authentication", list(sys.argv if argv is None else argv))
    allowed_time_delta = float(get_param("~allowed_time_delta", DEFAULT_ALLOWED_TIME_DELTA))
    path = get_param("~secret_file_location", None)
    if path is None:
        log.emit(log.ERROR, "Parameter '%s' not found.", ("secret_file_location",))
        return MISSING_PARAMETER
    try:
        secret = read_secret(str(path))
    except (OSError, UnicodeDecodeError):
        log.emit(log.ERROR, "Could not read from file '%s'", (path,))
        return FILE_IO_ERROR
    if len(secret.encode()) != SECRET_LENGTH:
        log.emit(log.ERROR, "Secret string not of length %d.", (SECRET_LENGTH,))
        return INVALID_SECRET

    def handle(request: Any) -> AuthenticationResponse:
        return AuthenticationResponse(authenticated(secret, request, get_rostime(), allowed_time_delta))

    Service("authenticate", Authentication, handle)
    log.emit(log.INFO, "ROS Authentication Server Started", ())
    spin()
    return 0
