#!/usr/bin/env sh
# Builds the Python module with nothing but a C compiler: meshfix.h's
# implementation as a shared library (python/meshfix/_native.c) next to a
# copy of python/meshfix/__init__.py, in OUTDIR/meshfix (default
# build/python/meshfix). Then: PYTHONPATH=OUTDIR python3 -c "import meshfix",
# or copy OUTDIR/meshfix into site-packages. NumPy is the only run-time need.
# Usage: python/build.sh [OUTDIR]     CC and CFLAGS are honoured.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(dirname "$here")
out=${1:-$root/build/python}
CC=${CC:-cc}
CFLAGS=${CFLAGS:--O2}
case "$(uname -s)" in
Darwin) library=_libmeshfix.dylib ;;
*) library=_libmeshfix.so ;;
esac
mkdir -p "$out/meshfix"
# shellcheck disable=SC2086
$CC -std=c99 $CFLAGS -fPIC -shared -fvisibility=hidden -I"$root" "$here/meshfix/_native.c" \
    -o "$out/meshfix/$library.tmp" -lm
mv "$out/meshfix/$library.tmp" "$out/meshfix/$library"
cp "$here/meshfix/__init__.py" "$out/meshfix/__init__.py"
echo "built $out/meshfix ($library)"
