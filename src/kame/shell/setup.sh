# kame: the ROS 1 environment for POSIX shells (ROS_* variables, PATH, workspaces).
#
# bash and zsh users source setup.bash / setup.zsh (which also define roscd & co and tab
# completion). A sourced file cannot learn its own path in sh, so from sh set
# _KAME_SETUP_DIR to this folder first:  _KAME_SETUP_DIR=/path/to/kame/shell . /path/to/kame/shell/setup.sh
# (the setup.sh files catkin_make writes into devel/ do that for you).
#
# The interpreter kame runs on is $_KAME_PYTHON when set, else $KAME_PYTHON, else the one whose
# site-packages holds this file, else a .venv/venv next to a source checkout, else a
# python3 on PATH that can import kame. _KAME_WORKSPACES (devel folders, ':'-separated,
# underlays first) is what a workspace's setup file adds on top.

if [ -z "${_KAME_SETUP_DIR:-}" ] || [ ! -f "$_KAME_SETUP_DIR/setup.sh" ]; then
    echo "kame: cannot tell where setup.sh is; source setup.bash or setup.zsh, or set _KAME_SETUP_DIR to its folder" >&2
    return 1
fi

if [ -z "${_KAME_PYTHON:-}" ] || [ ! -x "${_KAME_PYTHON:-}" ]; then
    _KAME_PYTHON=""
    if [ -n "${KAME_PYTHON:-}" ] && [ -x "$KAME_PYTHON" ]; then
        _KAME_PYTHON=$KAME_PYTHON
    fi
    if [ -z "$_KAME_PYTHON" ]; then
        case "$_KAME_SETUP_DIR" in
            */lib/python3*/site-packages/kame/shell|*/lib/python3*/dist-packages/kame/shell)
                _kame_prefix=${_KAME_SETUP_DIR%/lib/python3*}
                for _kame_candidate in "$_kame_prefix/bin/python3" "$_kame_prefix/bin/python"; do
                    if [ -z "$_KAME_PYTHON" ] && [ -x "$_kame_candidate" ]; then _KAME_PYTHON=$_kame_candidate; fi
                done
                unset _kame_prefix ;;
            */src/kame/shell)
                _kame_checkout=${_KAME_SETUP_DIR%/src/kame/shell}
                for _kame_candidate in "$_kame_checkout/.venv/bin/python" "$_kame_checkout/venv/bin/python"; do
                    if [ -z "$_KAME_PYTHON" ] && [ -x "$_kame_candidate" ]; then _KAME_PYTHON=$_kame_candidate; fi
                done
                unset _kame_checkout ;;
        esac
        unset _kame_candidate
    fi
    if [ -z "$_KAME_PYTHON" ]; then
        _kame_candidate=$(command -v python3 2>/dev/null)
        if [ -n "$_kame_candidate" ] && "$_kame_candidate" -c "import kame.shell" 2>/dev/null; then
            _KAME_PYTHON=$_kame_candidate
        fi
        unset _kame_candidate
    fi
    if [ -z "$_KAME_PYTHON" ]; then
        echo "kame: cannot find the Python interpreter kame is installed in; set KAME_PYTHON to it" >&2
        return 1
    fi
fi

_kame_env=$("$_KAME_PYTHON" -m kame.shell.environment --python "$_KAME_PYTHON" --workspaces "${_KAME_WORKSPACES:-}") || {
    echo "kame: $_KAME_PYTHON cannot run kame (python -m kame.shell.environment failed)" >&2
    unset _kame_env
    return 1
}
eval "$_kame_env"
unset _kame_env _KAME_WORKSPACES
