# kame: source this from bash for the ROS 1 environment, roscd/rosls/rosed/roscp/roscat
# and tab completion of the ros* tools.  Its path: `kame-setup --path`.
_KAME_SETUP_DIR=$(builtin cd -- "$(dirname -- "${BASH_SOURCE[0]}")" > /dev/null && pwd)
if . "$_KAME_SETUP_DIR/setup.sh"; then
    . "$_KAME_SETUP_DIR/rosbash.sh"
    . "$_KAME_SETUP_DIR/completion.bash"
fi
