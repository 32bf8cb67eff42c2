#!/usr/bin/env sh
# Builds the Blender add-on, a zip to install with Edit > Preferences >
# Add-ons > Install: blender/*.py as the package meshfix_blender, and inside
# it the meshfix Python module as python/build.sh builds it (meshfix.h's
# implementation as a shared library for this machine, and
# python/meshfix/__init__.py), imported as meshfix_blender.meshfix so that
# another meshfix on Blender's path is not in the way.
# Usage: blender/build.sh [ZIP]   (default build/meshfix_blender.zip)
# CC and CFLAGS go to python/build.sh; PYTHON (default python3) zips.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(dirname "$here")
zip=${1:-$root/build/meshfix_blender.zip}
case "$zip" in /*) ;; *) zip="$(pwd)/$zip" ;; esac
stage=$(dirname "$zip")/meshfix_blender.stage
rm -rf "$stage"
mkdir -p "$stage/meshfix_blender"
sh "$root/python/build.sh" "$stage/meshfix_blender" >/dev/null
cp "$here/__init__.py" "$here/repair.py" "$stage/meshfix_blender/"
rm -f "$zip.tmp"
(cd "$stage" && "${PYTHON:-python3}" -m zipfile -c "$zip.tmp" meshfix_blender)
mv "$zip.tmp" "$zip"
rm -rf "$stage"
echo "built $zip"
