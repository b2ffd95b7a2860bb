#!/usr/bin/env bash
# The whole test run against the newest versions of every dependency and extra that pip resolves
# today, or against the oldest that pyproject.toml allows (each in its own venv, .venv-newest or
# .venv-oldest, listed in its installed.txt). Run both before widening or narrowing a bound.
# Usage: scripts/dependency-sweep.sh newest|oldest [pytest args...]
set -euo pipefail
cd "$(dirname "$0")/.."
case ${1:-} in
  newest|oldest) ;;
  *) echo "usage: scripts/dependency-sweep.sh newest|oldest [pytest args...]" >&2; exit 2 ;;
esac
deps=$1
shift
KAME_VENV=".venv-$deps" KAME_DEPS=$deps exec bash scripts/test.sh "$@"
