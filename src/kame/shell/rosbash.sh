# kame: roscd, rospd, rosd, rosls, rosed, roscp, roscat and rosawesome as rosbash defines them, for bash
# and zsh (sourced by setup.bash / setup.zsh). Lookups go to `python -m kame.shell.locate`,
# which finds packages as rospack does.

_kame_locate() {
    "$_KAME_PYTHON" -m kame.shell.locate "$@"
}

# The first catkin workspace (a folder holding .catkin) listed in CMAKE_PREFIX_PATH.
_kame_first_workspace() {
    local _kame_rest _kame_ws
    _kame_rest=${CMAKE_PREFIX_PATH:-}
    while [ -n "$_kame_rest" ]; do
        _kame_ws=${_kame_rest%%:*}
        if [ "$_kame_ws" = "$_kame_rest" ]; then _kame_rest=""; else _kame_rest=${_kame_rest#*:}; fi
        if [ -n "$_kame_ws" ] && [ -f "$_kame_ws/.catkin" ]; then
            printf '%s\n' "$_kame_ws"
            return 0
        fi
    done
    return 1
}

roscd() {
    local _kame_dir
    if [ "$1" = "--help" ] || [ $# -gt 1 ]; then
        printf 'usage: roscd package\n\nJump to target package.\n'
        return 0
    fi
    if [ -z "$1" ]; then
        if [ -n "${ROS_WORKSPACE:-}" ]; then
            cd "$ROS_WORKSPACE"
            return 0
        fi
        if _kame_dir=$(_kame_first_workspace); then
            cd "$_kame_dir"
            return 0
        fi
        echo "Neither ROS_WORKSPACE is set nor a catkin workspace is listed in CMAKE_PREFIX_PATH.  Please set ROS_WORKSPACE or source a catkin workspace to use roscd with no arguments."
        return 1
    fi
    if ! _kame_dir=$(_kame_locate find "$1"); then
        echo "roscd: No such package/stack '$1'"
        return 1
    fi
    cd "$_kame_dir"
}

rosd() {
    local _kame_count _kame_item
    if [ "$1" = "--help" ]; then
        printf 'usage: rosd\n\nDisplays the list of currently remembered directories with indexes.\n'
        return 0
    fi
    _kame_count=0
    for _kame_item in $(dirs); do
        echo "$_kame_count $_kame_item"
        _kame_count=$((_kame_count + 1))
    done
}

rospd() {
    local _kame_dir
    if [ "$1" = "--help" ]; then
        printf 'usage: rospd\n\nLike pushd, also accepts indexes from rosd.\n'
        return 0
    fi
    case "$1" in
        ''|*[!0-9]*)
            if ! _kame_dir=$(_kame_locate find "$1") && [ $# -gt 0 ]; then
                echo "rospd: No such package/stack '$1'"
                return 1
            fi
            pushd "$_kame_dir" > /dev/null ;;
        *)
            pushd "+$1" > /dev/null ;;
    esac
    rosd
}

rosls() {
    if [ "$1" = "--help" ]; then
        printf 'usage: rosls [package]\n\nLists contents of a package directory.\n'
        return 0
    fi
    ls "$(_kame_locate find "$1")"
}

# Sets _kame_arg to the one file called $2 in package $1 (asking when there are several).
_kame_roscmd() {
    local _kame_hits _kame_status _kame_count _kame_choice
    _kame_arg=""
    _kame_hits=$(_kame_locate file "$1" "$2")
    _kame_status=$?
    if [ $_kame_status -eq 2 ]; then
        echo "Couldn't find package [$1]"
        return 1
    fi
    if [ -z "$_kame_hits" ]; then
        echo "That file does not exist in that package."
        return 1
    fi
    _kame_count=$(printf '%s\n' "$_kame_hits" | wc -l)
    if [ "$_kame_count" -gt 1 ]; then
        echo "You have chosen a non-unique filename, please pick one of the following:"
        printf '%s\n' "$_kame_hits" | awk '{ printf "%d) %s\n", NR, $0 }' >&2
        printf '%s' "${PS3:-#? }" >&2
        read -r _kame_choice
        _kame_arg=$(printf '%s\n' "$_kame_hits" | sed -n "${_kame_choice}p" 2> /dev/null)
        echo "$_kame_arg"
    else
        _kame_arg=$_kame_hits
    fi
}

rosed() {
    local _kame_arg
    if [ "$1" = "--help" ]; then
        printf 'usage: rosed [package] [file]\n\nEdit a file within a package.\n'
        return 0
    fi
    _kame_roscmd "$1" "$2"
    if [ -n "$_kame_arg" ]; then
        if [ -z "${EDITOR:-}" ]; then
            vim "$_kame_arg"
        else
            $EDITOR "$_kame_arg"
        fi
    fi
}

roscp() {
    local _kame_arg
    if [ "$1" = "--help" ] || [ $# -ne 3 ]; then
        printf 'usage: roscp package filename target\n\nCopy a file from a package to target location.\n'
        return 0
    fi
    _kame_roscmd "$1" "$2"
    if [ -n "$_kame_arg" ]; then
        cp "$_kame_arg" "$3"
    fi
}

roscat() {
    local _kame_arg
    if [ "$1" = "--help" ] || [ $# -ne 2 ]; then
        printf 'usage: roscat [package] [file]\n\nDisplay a file content within a package.\n'
        [ "$1" = "--help" ] && return 0 || return 1
    fi
    _kame_roscmd "$1" "$2" || return 1
    if [ -n "$_kame_arg" ]; then
        if [ -z "${CATTER:-}" ]; then
            cat "$_kame_arg"
        else
            $CATTER "$_kame_arg"
        fi
    fi
}

rosawesome() {
    alias megamaid='rosbag record'
    alias suck2blow='rosbag play'
    alias botherder=roscore
}
