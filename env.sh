# Source me from bash at the repo root:  source env.sh
# Activates the project's virtual environment (.venv) and the colcon install (install/), and keeps
# DDS on this machine: ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST and a ROS_DOMAIN_ID of this shell's
# own (kept if you already set one). `make setup` builds what this needs.
_bm_root="$(cd "$(dirname "${BASH_SOURCE[0]:-$0}")" && pwd)"
if [ ! -x "$_bm_root/.venv/bin/python" ] || [ ! -f "$_bm_root/install/setup.bash" ]; then
    echo "env.sh: the environment is not built yet; run 'make setup' in $_bm_root first" >&2
    return 1 2>/dev/null || exit 1
fi
# The activate and colcon scripts read unset variables: allow that while they run (make uses -u).
case $- in *u*) _bm_nounset=1; set +u ;; *) _bm_nounset= ;; esac
# shellcheck disable=SC1091
source "$_bm_root/.venv/bin/activate"
# rclpy's logging needs a writable home and log directory.
export HOME="${HOME:-$_bm_root}"
export ROS_LOG_DIR="${ROS_LOG_DIR:-$_bm_root/log/ros}"
# The wheels install ROS 2 into the venv prefix: ament's resource index lives there.
export AMENT_PREFIX_PATH="$_bm_root/.venv${AMENT_PREFIX_PATH:+:$AMENT_PREFIX_PATH}"
export CMAKE_PREFIX_PATH="$_bm_root/.venv${CMAKE_PREFIX_PATH:+:$CMAKE_PREFIX_PATH}"
# shellcheck disable=SC1091
COLCON_TRACE= source "$_bm_root/install/setup.bash"
[ -n "$_bm_nounset" ] && set -u
export RMW_IMPLEMENTATION="${RMW_IMPLEMENTATION:-rmw_fastrtps_cpp}"
# DDS stays on loopback; every shell gets its own domain unless one is given.
export ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST
export ROS_DOMAIN_ID="${ROS_DOMAIN_ID:-$(( ($$ % 100) + 1 ))}"
unset _bm_root _bm_nounset
