#!/bin/sh
# Entry point: bench/msg_bench.sh [--reps N] [--json FILE] ... (see msg_bench.py --help)
here=$(dirname "$0")
. "$here/compiled.sh"
py=/usr/bin/python3
[ -x "$py" ] || py=python3
exec "$py" "$here/msg_bench.py" "$@"
