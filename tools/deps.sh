#!/bin/sh
# Makes sure the Debian packages softrast builds and tests with are installed
# (or, given as arguments, the packages another target needs). As root it
# installs what is missing; otherwise it prints the exact command and fails.
set -eu
PACKAGES="build-essential pkg-config python3 libcglm-dev libsdl2-dev libsdl2-image-dev libpng-dev libcjson-dev libopenexr-dev libassimp-dev libexpat1-dev assimp-testmodels libcriterion-dev libgmp-dev xvfb xauth parallel clang libclang-rt-14-dev llvm python3-dev python3-numpy python3-pytest python3-setuptools python3-venv"
[ $# -gt 0 ] && PACKAGES="$*"
missing=""
for p in $PACKAGES; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing="$missing $p"
done
[ -z "$missing" ] && exit 0
if [ "$(id -u)" -eq 0 ]; then
    echo "softrast: installing missing packages:$missing"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq
    apt-get install -y -qq $missing >/dev/null
else
    echo "softrast: missing packages; install them with:" >&2
    echo "    sudo apt-get install -y$missing" >&2
    exit 1
fi
