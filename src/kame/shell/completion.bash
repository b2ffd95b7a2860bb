# kame: bash tab completion for the ros* tools (sourced by setup.bash). Candidates come from
# `python -m kame.shell.complete COMP_CWORD COMP_WORDS...`: subcommands, options, package
# names and folders, executables, message types, and live topic, node, service and
# parameter names from the master.

_kame_complete() {
    local IFS=$'\n'
    COMPREPLY=($("$_KAME_PYTHON" -m kame.shell.complete "$COMP_CWORD" "${COMP_WORDS[@]}" 2> /dev/null))
    if [[ ${#COMPREPLY[@]} -eq 1 && ${COMPREPLY[0]} == */ ]]; then
        compopt -o nospace 2> /dev/null
    fi
    return 0
}

complete -o default -F _kame_complete rostopic rosnode rosservice rosparam rosmsg rossrv rospack rosstack \
    rosbag rosclean rosrun roslaunch rosed roscat roscp rosversion roscore rosmaster roswtf rosout \
    catkin catkin_make catkin_create_pkg
complete -o nospace -F _kame_complete roscd rosls rospd
