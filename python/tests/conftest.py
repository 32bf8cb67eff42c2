"""Fixtures: the C reference program (cref.c, built here from meshfix.h with
the C compiler) and a runner that gives it the same arrays as the binding."""
import os
import shlex
import subprocess

import numpy as np
import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))


@pytest.fixture(scope="session")
def cref(tmp_path_factory):
    out = tmp_path_factory.mktemp("cref")
    exe = str(out / "cref")
    cc = shlex.split(os.environ.get("CC", "cc"))
    subprocess.run(cc + ["-std=c99", "-O2", "-I" + ROOT, os.path.join(HERE, "cref.c"), "-o", exe, "-lm"],
                   check=True)
    return CRef(exe, out)


class CRef:
    """Runs one call of the C library on raw copies of the arrays."""

    def __init__(self, exe, directory):
        self.exe = exe
        self.directory = directory
        self.count = 0

    def _file(self, array, name):
        self.count += 1
        path = str(self.directory / ("%s_%d.bin" % (name, self.count)))
        np.ascontiguousarray(array).tofile(path)
        return path

    def __call__(self, mode, indices=None, positions=None, **keys):
        args = [self.exe, mode]
        if indices is not None:
            indices = np.ascontiguousarray(indices)
            args += ["indices=" + self._file(indices, "indices"), "index_size=%d" % indices.itemsize]
        if positions is not None:
            positions = np.ascontiguousarray(positions)
            args += ["positions=" + self._file(positions, "positions"), "position_size=%d" % positions.itemsize]
        elif indices is not None:
            args.append("vertex_count=%d" % (int(indices.max()) + 1))
        for name in ("triangle_normals", "vertex_normals"):
            if keys.get(name) is not None:
                args.append("%s=%s" % (name, self._file(np.asarray(keys.pop(name), np.float32), name)))
            keys.pop(name, None)
        out = str(self.directory / ("out_%d.bin" % self.count))
        args.append("out=" + out)
        args += ["%s=%s" % (k, int(v) if isinstance(v, bool) else v) for k, v in keys.items()]
        run = subprocess.run(args, check=True, capture_output=True, text=True)
        fields = dict(line.split("=", 1) for line in run.stdout.splitlines())
        data = np.fromfile(out, dtype=np.uint8) if os.path.exists(out) else np.zeros(0, np.uint8)
        return fields, data
