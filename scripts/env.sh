# Sourced by the other scripts: repository root, workspace, and a PATH with the system python
# (Debian's ROS python modules live there; a pyenv python first on PATH lacks them).
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
WS="$ROOT/.ws"
export PATH="/usr/bin:$PATH"
