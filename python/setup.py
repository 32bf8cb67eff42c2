"""Builds meshfix.h's implementation into the package as a shared library
(meshfix/_libmeshfix*.so, loaded with ctypes: no Python headers involved).

    /usr/bin/python3 -m pip wheel --no-build-isolation --no-deps --no-index -w build/wheels ./python

from the checkout, offline: Debian's python3-setuptools and python3-wheel do
the build; README.md has the venv install that follows.

The header is taken from MESHFIX_HEADER_DIR, else the directory above this
one (the repository), else this directory."""
import os
import re
import sys

from setuptools import Extension, setup

here = os.path.dirname(os.path.abspath(__file__))
candidates = [os.environ.get("MESHFIX_HEADER_DIR"), os.path.dirname(here), here]
header_dir = next((d for d in candidates if d and os.path.isfile(os.path.join(d, "meshfix.h"))), None)
if header_dir is None:
    sys.exit("meshfix: meshfix.h not found above %s; set MESHFIX_HEADER_DIR" % here)
with open(os.path.join(header_dir, "meshfix.h"), encoding="utf-8") as f:
    text = f.read()
version = ".".join(re.search(r"^#define MESHFIX_VERSION_%s +(\d+)" % part, text, re.M).group(1)
                   for part in ("MAJOR", "MINOR", "PATCH"))

unix = not sys.platform.startswith("win")
setup(
    version=version,
    packages=["meshfix"],
    ext_modules=[Extension(
        "meshfix._libmeshfix",
        sources=["meshfix/_native.c"],
        include_dirs=[header_dir],
        depends=[os.path.join(header_dir, "meshfix.h")],
        libraries=["m"] if unix else [],
        extra_compile_args=["-std=c99", "-fvisibility=hidden"] if unix else [],
    )],
)
