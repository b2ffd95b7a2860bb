#!/usr/bin/env bash
# Installs the real web clients the bridge tests (tests/web) drive: Debian's Chromium, run headless,
# and the npm packages pinned in tests/web/package-lock.json (roslibjs, Foxglove's WebSocket client
# and ROS 1 message parser, the MCAP reader), into tests/web/node_modules. Test peers only, never a
# kame dependency. Without apt, root or npm it says so and exits 0: those tests then skip.
set -euo pipefail
cd "$(dirname "$0")/.."
if command -v apt-get >/dev/null 2>&1 && [ "$(id -u)" = 0 ]; then
  missing=()
  dpkg-query -W -f='${Status}' chromium 2>/dev/null | grep -q 'install ok installed' || missing+=(chromium)
  # Node may come from elsewhere than Debian (with its own npm): Debian's is installed only when none is
  command -v node >/dev/null 2>&1 || missing+=(nodejs npm)
  if [ ${#missing[@]} -ne 0 ]; then
    echo "install-web-peers: installing ${missing[*]}" >&2
    apt-get update -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
  fi
else
  echo "install-web-peers: no apt-get or not root; the browser tests will be skipped" >&2
fi
if ! command -v npm >/dev/null 2>&1; then
  echo "install-web-peers: no npm; the web-client tests will be skipped" >&2
  exit 0
fi
if [ ! -d tests/web/node_modules ] || [ tests/web/package-lock.json -nt tests/web/node_modules ]; then
  (cd tests/web && npm ci --no-audit --no-fund --loglevel=error >/dev/null)
fi
