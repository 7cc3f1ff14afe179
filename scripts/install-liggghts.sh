#!/usr/bin/env bash
# Installs LIGGGHTS 3.8 (the Debian package `liggghts`, binary `liggghts`) from the Debian
# archive when `liggghts` is not on the PATH; does nothing when it is. Used by
# scripts/bench-vs-liggghts.sh, scripts/cross-check-bed.sh and scripts/cross-check-contacts.sh.
#
# Runs apt-get as root, or through sudo when not root; noninteractive and quiet, with all of
# apt's output on stderr (stdout stays free for the caller's results). Exits non-zero when the
# install fails or leaves no `liggghts` binary.
#
# Usage: scripts/install-liggghts.sh
set -euo pipefail

if command -v liggghts >/dev/null 2>&1; then
    exit 0
fi

echo "installing LIGGGHTS 3.8 from the Debian archive (package liggghts)" >&2
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then
    command -v sudo >/dev/null 2>&1 || {
        echo "install-liggghts.sh: not root and no sudo; install the package liggghts" >&2
        exit 1
    }
    sudo_cmd=(sudo)
fi
"${sudo_cmd[@]}" apt-get update -qq >&2
DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq liggghts >&2

command -v liggghts >/dev/null 2>&1 || {
    echo "install-liggghts.sh: the package installed but no liggghts binary is on the PATH" >&2
    exit 1
}
