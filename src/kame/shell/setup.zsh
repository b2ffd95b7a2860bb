# kame: source this from zsh for the ROS 1 environment and roscd/rosls/rosed/roscp/roscat
# (tab completion too when compinit is loaded).  Its path: `kame-setup --path --shell zsh`.
_KAME_SETUP_DIR=${${(%):-%x}:A:h}
if emulate sh -c '. "$_KAME_SETUP_DIR/setup.sh"'; then
    . "$_KAME_SETUP_DIR/rosbash.sh"
    if (( $+functions[compdef] )); then
        autoload -U +X bashcompinit && bashcompinit && . "$_KAME_SETUP_DIR/completion.bash"
    fi
fi
