#!/usr/bin/env bash
# The whole test run (scripts/test.sh) against the newest versions of every dependency and extra
# that pip resolves today, or against the oldest that pyproject.toml allows. Like CI, it runs on a
# fresh clone of the committed HEAD (in build/sweep/newest or build/sweep/oldest, with its own
# .venv, whose installed.txt lists what was tested). Run both before moving a bound.
# Usage: scripts/dependency-sweep.sh newest|oldest [pytest args...]
set -euo pipefail
cd "$(dirname "$0")/.."
case ${1:-} in
  newest|oldest) ;;
  *) echo "usage: scripts/dependency-sweep.sh newest|oldest [pytest args...]" >&2; exit 2 ;;
esac
deps=$1
shift
clone="build/sweep/$deps"
rm -rf "$clone"
git clone -q . "$clone"
cd "$clone"
KAME_DEPS=$deps exec bash scripts/test.sh "$@"
