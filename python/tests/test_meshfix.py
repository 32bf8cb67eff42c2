"""The Python binding against the C library on the same meshes: real models
from Debian's assimp-testmodels and occt-misc, as given and with a third of
their triangles turned, through every index and position format; each
result (new indices, flipped flags, patch ids, every report field, the
check's reason, the weld's remap) must be the C program's, exactly."""
import json
import os
import re
import subprocess
import sys

import numpy as np
import pytest

import meshfix
import models
from conftest import ROOT

# ---- helpers ----


def flat(report):
    """The report as cref prints it: name -> text."""
    out = {"verdict": str(int(report.verdict)), "verdict_before": str(int(report.verdict_before)),
           "summary": report.summary}
    for name in ("triangles_flipped", "patches_flipped", "patches_doubtful", "triangles_doubtful",
                 "area_doubtful", "edges_inconsistent_before", "patches_inside_out_before", "signed_volume_before"):
        out[name] = getattr(report, name)
    for group in ("mesh", "evidence"):
        for name, value in vars(getattr(report, group)).items():
            out[group + "." + name] = value
    return out


def same_report(py, c):
    mine = flat(py)
    assert c["result"] == "0"
    theirs = {k: v for k, v in c.items() if k != "result"}
    assert set(mine) == set(theirs), "fields differ: %s" % sorted(set(mine) ^ set(theirs))
    for name, value in mine.items():
        if isinstance(value, float):
            assert value == float(theirs[name]), name
        elif isinstance(value, int):
            assert value == int(theirs[name]), name
        else:
            assert value == theirs[name], name


def load(name):
    path = models.MODELS[name]
    if not os.path.exists(path):
        package = models.package_of(path)
        pytest.skip("the models of %s are missing (apt-get install %s)" % (package, package))
    return models.load(name)


def scramble(indices, share=1 / 3, seed=14):
    """Turns a seeded random share of the triangles: (a, b, c) -> (a, c, b)."""
    rng = np.random.default_rng(seed)
    turned = rng.random(len(indices)) < share
    out = indices.copy()
    out[turned] = out[turned][:, [0, 2, 1]]
    return out


MODEL_NAMES = list(models.MODELS)

VARIANTS = {  # name: (scrambled, index dtype, position dtype, options)
    "as-given": (False, np.uint32, np.float32, {}),
    "scrambled": (True, np.uint32, np.float32, {}),
    "scrambled-uint16": (True, np.uint16, np.float32, {}),
    "scrambled-float64": (True, np.uint32, np.float64, {}),
    "scrambled-uint16-float64": (True, np.uint16, np.float64, {}),
    "scrambled-seed": (True, np.uint32, np.float32, {"policy": "seed"}),
    "scrambled-majority": (True, np.uint32, np.float32, {"policy": "majority"}),
    "scrambled-outward": (True, np.uint32, np.float32, {"policy": "outward"}),
    "scrambled-visibility": (True, np.uint32, np.float32, {"policy": "visibility"}),
    "scrambled-indices": (True, np.uint32, np.float32, {"topology": "indices"}),
    "scrambled-no-positions": (True, np.uint32, None, {}),
}


def c_keys(options):
    keys = {}
    if "policy" in options:
        keys["policy"] = int(meshfix.Policy[options["policy"].upper()])
    if "topology" in options:
        keys["topology"] = int(meshfix.Topology[options["topology"].upper()])
    return keys


def mesh_variant(name, variant):
    mesh = load(name)
    scrambled, index_dtype, position_dtype, options = VARIANTS[variant]
    indices = scramble(mesh["indices"]) if scrambled else mesh["indices"]
    if index_dtype == np.uint16 and len(mesh["positions"]) > 65535:
        pytest.skip("more than 65535 vertices")
    positions = None if position_dtype is None else mesh["positions"].astype(position_dtype)
    return mesh, indices.astype(index_dtype), positions, options


# ---- the module ----


def test_version_is_the_headers():
    with open(os.path.join(ROOT, "meshfix.h")) as f:
        text = f.read()
    parts = [re.search(r"#define MESHFIX_VERSION_%s (\d+)" % p, text).group(1) for p in ("MAJOR", "MINOR", "PATCH")]
    assert meshfix.__version__ == ".".join(parts)


def header_list(macro):
    """(name, text) of each X(name, "text") in one of meshfix.h's X-macro lists."""
    with open(os.path.join(ROOT, "meshfix.h")) as f:
        body = re.search(r"#define %s\(X\)((?:.*\\\n)*.*)" % macro, f.read()).group(1)
    return re.findall(r'X\((\w+), "((?:[^"\\]|\\.)*)"\)', body)


def test_result_names_are_the_headers():
    """Every code of MESHFIX_RESULT_LIST has its name and the library's text."""
    results = header_list("MESHFIX_RESULT_LIST")
    assert ("MESHFIX_ERROR_NORMALS_REQUIRED", results[-1][1]) == results[-1]
    for code, (name, text) in enumerate(results):
        e = meshfix.MeshfixError(code)
        assert e.result == code and e.name == name and str(e) == "%s: %s" % (name, text)


def header_policies():
    """MESHFIX_POLICY_LIST as the header writes it: (enum name, name, description, the five flags
    of PolicyInfo). The list's four needs are flags; a policy casts rays unless it decides by PATCH
    (the list's last two columns, how it decides and its confidence, are the library's own)."""
    with open(os.path.join(ROOT, "meshfix.h")) as f:
        body = re.search(r"#define MESHFIX_POLICY_LIST\(X\)(.*?)\n\n", f.read(), re.S).group(1)
    rows = []
    for enum_name, name, text, flags, decides, _ in re.findall(
            r'X\(MESHFIX_POLICY_(\w+), "(\w+)", ((?:"[^"]*"\s*\\?\s*)+), ([01, ]+), (\w+), (\w+)\)', body):
        rows.append((enum_name, name, "".join(re.findall(r'"([^"]*)"', text)),
                     tuple(bool(int(x)) for x in flags.split(",")) + (decides != "PATCH",)))
    return rows


def test_policy_is_the_headers():
    """Policy's members are meshfix_policy's, by name and value (MESHFIX_POLICY_COUNT left out), and
    policy_info() says of each what the header's list says."""
    rows = header_policies()
    assert len(rows) == 8
    assert [(p.name, p.value) for p in meshfix.Policy] == [(r[0], i) for i, r in enumerate(rows)]
    assert meshfix.Policy.NORMALS == 7 and isinstance(meshfix.Policy.UP, int)
    for policy, (_, name, text, flags) in zip(meshfix.Policy, rows):
        info = meshfix.policy_info(policy)
        assert info == meshfix.PolicyInfo(name, text, *flags)
        assert meshfix.policy_info(name) == info == meshfix.policy_info(int(policy))
    assert meshfix.policy_info("sdf").needs_distance and meshfix.policy_info("up").reads_up
    with pytest.raises(ValueError, match="unknown policy"):
        meshfix.policy_info(len(rows))


def test_docstring_lists_the_headers_policies():
    """The module's docstring and python/README.md name every policy the header lists, in its
    order, and no other."""
    names = [r[1] for r in header_policies()]
    listed = re.search(r'policy=(.*?)\(or a Policy', meshfix.__doc__, re.S).group(1)
    assert re.findall(r'"(\w+)"', listed) == names
    with open(os.path.join(ROOT, "python", "README.md")) as f:
        listed = re.search(r"`policy` \((.*?)\)", f.read(), re.S).group(1)
    assert re.findall(r'"(\w+)"', listed) == names


def test_doubtful_below_is_the_reports():
    """doubtful_below() is the bar the report counts patches doubtful by: 0.9 under auto, 0.5 under
    the others, min_confidence where higher; a patch just under it is counted, one at it is not."""
    assert meshfix.doubtful_below() == pytest.approx(0.9)
    assert meshfix.doubtful_below("majority") == meshfix.doubtful_below("visibility") == 0.5
    assert meshfix.doubtful_below("seed", evidence=dict(min_confidence=0.75)) == 0.75
    assert meshfix.doubtful_below("auto", evidence=dict(min_confidence=0.25)) == pytest.approx(0.9)
    positions = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], np.float32)
    indices = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 3, 2]], np.uint32)
    _, report, out = meshfix.orient(indices, positions, outputs=True)
    confidence = float(out.patch_confidence[0])
    _, below, _ = meshfix.orient(indices, positions, outputs=True,
                                 evidence=dict(min_confidence=np.nextafter(np.float32(confidence), np.float32(2))))
    assert report.patches_doubtful == 0 and below.patches_doubtful == 1


def test_policy_names_are_the_librarys(tmp_path):
    """The module takes its policy names from the library it loads
    (meshfix_policy_string): built from a header whose "up" is "upward",
    it has Policy.UPWARD and takes policy="upward", not "up"."""
    with open(os.path.join(ROOT, "meshfix.h")) as f:
        text = f.read()
    assert text.count('MESHFIX_POLICY_UP, "up", ') == 1
    (tmp_path / "meshfix.h").write_text(text.replace('MESHFIX_POLICY_UP, "up", ', 'MESHFIX_POLICY_UP, "upward", '))
    # build.sh puts CFLAGS' -I before the repository's: the changed header wins
    subprocess.run(["sh", os.path.join(ROOT, "python", "build.sh"), str(tmp_path / "module")], check=True,
                   capture_output=True, env=dict(os.environ, CFLAGS="-O0 -I%s" % tmp_path))
    script = """if True:
        import numpy as np, meshfix
        positions = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], np.float32)
        indices = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 3, 2]], np.uint32)
        assert meshfix.Policy.UPWARD == 6 and not hasattr(meshfix.Policy, "UP"), list(meshfix.Policy)
        assert meshfix.orient(indices, positions, policy="upward")[1].triangles_flipped > 0
        try:
            meshfix.orient(indices, positions, policy="up")
        except ValueError as e:
            assert "upward" in str(e), e
        else:
            raise AssertionError("policy='up' was taken")
        print(meshfix.__file__)
    """
    run = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, cwd=str(tmp_path),
                         env=dict(os.environ, PYTHONPATH=str(tmp_path / "module")))
    assert run.returncode == 0, run.stderr
    assert run.stdout.strip() == str(tmp_path / "module" / "meshfix" / "__init__.py")


def tetrahedron():
    positions = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], np.float32)
    indices = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 3, 2]], np.uint32)
    return indices, positions


def test_tetrahedron_one_flip(cref):
    indices, positions = tetrahedron()
    fixed, report = meshfix.orient(indices, positions)
    assert report.triangles_flipped == 1
    assert report.verdict == meshfix.Verdict.REPAIRED and str(report.verdict) == "repaired"
    assert report.summary == "fixed 1 triangle in 1 patch"
    assert fixed.dtype == np.uint32 and fixed.shape == (4, 3)
    assert fixed.tolist() == [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]
    assert indices[3].tolist() == [1, 3, 2], "the input is not changed"
    c, data = cref("orient", indices, positions)
    same_report(report, c)
    assert np.array_equal(data[:48].view(np.uint32).reshape(4, 3), fixed)
    assert meshfix.check(fixed, positions, "solid")
    assert json.loads(json.dumps(report.to_dict()))["verdict"] == "repaired"


@pytest.mark.parametrize("name", MODEL_NAMES)
@pytest.mark.parametrize("variant", list(VARIANTS))
def test_orient_as_c(cref, name, variant):
    mesh, indices, positions, options = mesh_variant(name, variant)
    fixed, report, out = meshfix.orient(indices, positions, outputs=True, **options)
    c, data = cref("orient", indices, positions, **c_keys(options))
    same_report(report, c)
    n = indices.size * indices.itemsize
    t = len(indices)
    assert fixed.dtype == indices.dtype and fixed.shape == indices.shape
    assert np.array_equal(fixed.reshape(-1), data[:n].view(indices.dtype)), "new indices differ from C's"
    assert np.array_equal(out.flipped, data[n:n + t].astype(bool)), "flipped flags differ from C's"
    assert np.array_equal(out.patch_ids, data[n + t:].view(np.uint32)), "patch ids differ from C's"
    assert out.flipped.sum() == report.triangles_flipped
    assert len(out.patch_confidence) == report.mesh.patches
    # what decided each patch, counted as the report counts it
    kinds = np.bincount(out.patch_evidence, minlength=6)
    e = report.evidence
    assert len(out.patch_evidence) == report.mesh.patches
    assert (kinds[meshfix.Evidence.VOLUME], kinds[meshfix.Evidence.PARITY], kinds[meshfix.Evidence.VISIBILITY],
            kinds[meshfix.Evidence.NORMALS], kinds[meshfix.Evidence.NONE] + kinds[meshfix.Evidence.POLICY]) == \
        (e.patches_by_volume, e.patches_by_parity, e.patches_by_visibility, e.patches_by_normals, e.patches_kept)
    assert len(out.components) == report.mesh.components
    assert out.components["triangles"].sum() == report.mesh.triangles - report.mesh.triangles_degenerate
    if variant.startswith("scrambled") and "policy" not in options and positions is not None:
        assert report.triangles_flipped > 0


@pytest.mark.parametrize("name", MODEL_NAMES)
def test_inspect_as_c(cref, name):
    mesh, indices, positions, _ = mesh_variant(name, "scrambled")
    report, out = meshfix.inspect(indices, positions, outputs=True)
    c, data = cref("inspect", indices, positions)
    same_report(report, c)
    assert np.array_equal(out.patch_ids, data.view(np.uint32))
    assert report.triangles_flipped == 0
    again = meshfix.inspect(indices.astype(np.uint16), positions.astype(np.float64))
    assert again.mesh.edges_inconsistent == report.mesh.edges_inconsistent


CHECKS = ["consistent", "closed", "manifold", "outward", "no_degenerate", "solid"]


@pytest.mark.parametrize("name", MODEL_NAMES)
@pytest.mark.parametrize("requirement", CHECKS)
@pytest.mark.parametrize("scrambled", [False, True], ids=["as-given", "scrambled"])
def test_check_as_c(cref, name, requirement, scrambled):
    mesh = load(name)
    indices = scramble(mesh["indices"]) if scrambled else mesh["indices"]
    result = meshfix.check(indices, mesh["positions"], requirement)
    c, _ = cref("check", indices, mesh["positions"], requirements=int(meshfix.Requirement[requirement.upper()]))
    assert bool(result) == (c["ok"] == "1")
    assert result.text == c["text"]
    assert int(result.requirement) == int(c["requirement"])
    assert result.count == int(c["count"])
    assert result.triangle == (None if c["triangle"] == "-1" else int(c["triangle"]))
    edge = tuple(int(v) for v in c["edge"].split())
    assert result.edge == (None if edge == (0xFFFFFFFF, 0xFFFFFFFF) else edge)
    assert result.result == "MESHFIX_OK"
    if scrambled and requirement == "consistent":
        assert not result and result.text.startswith("not consistent")


@pytest.mark.parametrize("name", [n for n in MODEL_NAMES if n.lower().endswith(".stl")])
@pytest.mark.parametrize("tolerance", [0.0, 1e-4])
@pytest.mark.parametrize("dtype", [np.float32, np.float64])
def test_weld_as_c(cref, name, tolerance, dtype):
    positions = load(name)["positions"].astype(dtype)
    remap, unique = meshfix.weld(positions, tolerance)
    c, data = cref("weld", None, positions, tolerance=repr(tolerance))
    assert c["result"] == "0"
    assert unique == int(c["unique"]) and unique < len(positions)
    assert np.array_equal(remap, data.view(np.uint32))
    assert (remap <= np.arange(len(positions))).all()


@pytest.mark.parametrize("name", [n for n in MODEL_NAMES if n.lower().endswith(".stl")])
def test_facet_normals_as_evidence_as_c(cref, name):
    mesh = load(name)
    indices = scramble(mesh["indices"])
    for policy in ("auto", "normals"):
        fixed, report = meshfix.orient(indices, mesh["positions"], policy=policy,
                                       evidence={"triangle_normals": mesh["triangle_normals"]})
        c, data = cref("orient", indices, mesh["positions"], triangle_normals=mesh["triangle_normals"],
                       **c_keys({"policy": policy}))
        same_report(report, c)
        assert np.array_equal(fixed.reshape(-1), data[:indices.nbytes].view(np.uint32))


def test_vertex_normals_and_an_interleaved_vertex_buffer(cref):
    """Wuson.ply's vertex rows (x y z nx ny nz s t, 32 bytes) go to C as they
    are, stride 32, no copy; the normals as a strided view of the same rows."""
    mesh = load("Wuson.ply")
    vertices = mesh["vertices"]
    assert vertices.shape[1] == 8
    indices = scramble(mesh["indices"])
    normals_view = vertices[:, 3:6]
    fixed, report = meshfix.orient(indices, vertices, policy="normals", evidence={"vertex_normals": normals_view})
    c, data = cref("orient", indices, mesh["positions"], vertex_normals=mesh["vertex_normals"],
                   **c_keys({"policy": "normals"}))
    same_report(report, c)
    assert np.array_equal(fixed.reshape(-1), data[:indices.nbytes].view(np.uint32))
    assert report.evidence.patches_by_normals > 0
    packed = meshfix.orient(indices, mesh["positions"])
    strided = meshfix.orient(indices, vertices)
    assert np.array_equal(packed[0], strided[0]) and flat(packed[1]) == flat(strided[1])


def test_normals_need_a_row_per_triangle_or_vertex():
    """C reads index_count / 3 triangle normals and vertex_count vertex
    normals: an array of any other length is refused before the call (one
    row for 12 triangles was read past its end)."""
    indices, positions = tetrahedron()
    normals = np.cross(positions[indices[:, 1]] - positions[indices[:, 0]],
                       positions[indices[:, 2]] - positions[indices[:, 0]])
    wide = np.hstack([normals, normals])  # rows of 6 floats: a strided view goes as it is
    for name, what in (("triangle_normals", "triangles"), ("vertex_normals", "vertices")):
        for given in (normals[:1], normals[:3], wide[:3, :3], np.vstack([normals, normals]), normals[:0]):
            message = r"meshfix: %s has %d rows?; the 4 %s need 4 \(one each\)" % (name, len(given), what)
            for call in (lambda **o: meshfix.orient(indices, positions, **o),
                         lambda **o: meshfix.orient(indices, None, **o),
                         lambda **o: meshfix.inspect(indices, positions, **o),
                         lambda **o: meshfix.check(indices, positions, **o),
                         lambda **o: meshfix.scratch_size(indices.size, len(positions), **o)):
                with pytest.raises(ValueError, match=message):
                    call(policy="normals", evidence={name: given})
        for given in (normals, wide[:, :3], normals.reshape(-1)):
            report = meshfix.orient(indices, positions, policy="normals", evidence={name: given})[1]
            # every patch by its normals (the turned face's triangle normal agrees with it: a patch of its own)
            assert report.evidence.patches_by_normals == report.mesh.patches >= 1
    # a soup of 200,000 triangles with one normal: the rest were heap garbage ("fixed 48724 triangles")
    soup = np.arange(600000, dtype=np.uint32).reshape(-1, 3)
    corners = np.random.default_rng(1).random((600000, 3)).astype(np.float32)
    with pytest.raises(ValueError, match="triangle_normals has 1 row; the 200000 triangles need 200000"):
        meshfix.orient(soup, corners, policy="normals", evidence={"triangle_normals": normals[:1]})


def test_threads_give_the_same_result():
    mesh = load("motor.stl")
    indices = scramble(mesh["indices"])
    for policy in ("auto", "visibility"):
        one = meshfix.orient(indices, mesh["positions"], policy=policy)
        many = meshfix.orient(indices, mesh["positions"], policy=policy, threads=2)
        assert np.array_equal(one[0], many[0])
        assert flat(one[1]) == flat(many[1])


def test_threads_every_task_ends_before_c_goes_on(monkeypatch):
    """options.parallel_for returns to C only when every task has run and
    none is running, even when the pool refuses a chunk: C then reads what
    the tasks wrote and frees the memory they write. The pool's error is
    raised after C returns. (A pool whose chunks take 0.2 s and which
    refuses all from the third, and meshfix_orient watched as it returns.)"""
    import concurrent.futures
    import threading
    import time
    mesh = load("motor.stl")
    indices = scramble(mesh["indices"])
    lock = threading.Lock()
    state = {"submitted": 0, "pending": 0, "pending_when_c_returned": None}

    class RefusingPool(concurrent.futures.ThreadPoolExecutor):
        def submit(self, fn, *args):
            state["submitted"] += 1
            if state["submitted"] >= 3:
                raise RuntimeError("the pool refuses a chunk")

            def slow():
                time.sleep(0.2)
                try:
                    return fn(*args)
                finally:
                    with lock:
                        state["pending"] -= 1
            with lock:
                state["pending"] += 1
            return super().submit(slow)

    orient_c = meshfix._orient

    def watched(*args):
        result = orient_c(*args)
        with lock:
            state["pending_when_c_returned"] = state["pending"]
        return result

    monkeypatch.setattr(concurrent.futures, "ThreadPoolExecutor", RefusingPool)
    monkeypatch.setattr(meshfix, "_orient", watched)
    with pytest.raises(RuntimeError, match="the pool refuses a chunk"):
        meshfix.orient(indices, mesh["positions"], threads=2)
    assert state["submitted"] > 3 and state["pending_when_c_returned"] == 0


def test_options_reach_c():
    mesh = load("sphereWithHole.stl")
    indices = scramble(mesh["indices"])
    few = meshfix.orient(indices, mesh["positions"], policy="visibility", visibility={"rays": 65536})[1]
    more = meshfix.orient(indices, mesh["positions"], policy="visibility", visibility={"rays": 262144})[1]
    assert few.evidence.rays_cast != more.evidence.rays_cast
    seeded = meshfix.orient(indices, mesh["positions"], policy="visibility", seed=7)[1]
    assert seeded.evidence.rays_cast > 0
    up = meshfix.orient(indices, mesh["positions"], policy="up", up=(0, 0, 1))[0]
    down = meshfix.orient(indices, mesh["positions"], policy="up", up=(0, 0, -1))[0]
    assert not np.array_equal(up, down)
    with pytest.raises(meshfix.MeshfixError) as e:
        meshfix.orient(indices, mesh["positions"], evidence={"sigma": -1})
    assert e.value.name == "MESHFIX_ERROR_INVALID_ARGUMENT"
    with pytest.raises(TypeError):
        meshfix.orient(indices, mesh["positions"], visibility={"raise": 1})
    with pytest.raises(ValueError):
        meshfix.orient(indices, mesh["positions"], policy="sideways")


def test_options_that_do_not_fit_their_c_field_are_refused():
    """ctypes wraps an integer to its field's width and makes a finite
    float beyond float's range infinite, silently; the binding refuses such
    a value with the library's MESHFIX_ERROR_INVALID_ARGUMENT, naming it."""
    indices, positions = tetrahedron()
    text = dict(header_list("MESHFIX_RESULT_LIST"))["MESHFIX_ERROR_INVALID_ARGUMENT"]
    calls = (lambda **o: meshfix.orient(indices, positions, **o), lambda **o: meshfix.inspect(indices, positions, **o),
             lambda **o: meshfix.check(indices, positions, **o), lambda **o: meshfix.weld(positions, **o),
             lambda **o: meshfix.scratch_size(indices.size, len(positions), **o))
    refused = [
        ("visibility.rays", {"visibility": {"rays": 2 ** 64 + 100}}), ("visibility.rays", {"visibility": {"rays": -1}}),
        ("visibility.rays", {"visibility": {"rays": 100.0}}), ("visibility.rays", {"visibility": {"rays": "100"}}),
        ("visibility.min_samples", {"visibility": {"min_samples": 2 ** 32}}),
        ("visibility.flags", {"visibility": {"flags": -1}}), ("visibility.c0", {"visibility": {"c0": 1e39}}),
        ("seed", {"seed": 2 ** 40}), ("seed", {"seed": -1}), ("seed", {"seed": 7.5}),
        ("policy", {"policy": 2 ** 32 + 1}), ("policy", {"policy": 1.0}), ("topology", {"topology": -2 ** 31 - 1}),
        ("weld_tolerance", {"weld_tolerance": -1e39}), ("up[2]", {"up": (0, 0, 1e300)}),
        ("evidence.sigma", {"evidence": {"sigma": 10 ** 400}}), ("evidence.min_confidence",
                                                                  {"evidence": {"min_confidence": "0.5"}}),
        ("sdf.step", {"sdf": {"step": 3.5e38}}), ("sdf.mode", {"sdf": {"mode": 2 ** 31}}),
    ]
    for option, options in refused:
        for call in calls:
            with pytest.raises(meshfix.MeshfixError) as e:
                call(**options)
            assert e.value.result == 1 and e.value.name == "MESHFIX_ERROR_INVALID_ARGUMENT", option
            assert e.value.option == option
            assert str(e.value).startswith("MESHFIX_ERROR_INVALID_ARGUMENT: %s (%s " % (text, option)), str(e.value)
    # the C arguments beside the options
    for option, call in (("tolerance", lambda: meshfix.weld(positions, 1e39)),
                         ("index_count", lambda: meshfix.scratch_size(-12, 4)),
                         ("index_count", lambda: meshfix.scratch_size(2 ** 64 + 12, 4)),
                         ("vertex_count", lambda: meshfix.scratch_size(12, 2 ** 64 + 4)),
                         ("requirements", lambda: meshfix.check(indices, positions, 2 ** 32 + 1)),
                         ("requirements", lambda: meshfix.check(indices, positions, ["closed", 1.0]))):
        with pytest.raises(meshfix.MeshfixError) as e:
            call()
        assert e.value.name == "MESHFIX_ERROR_INVALID_ARGUMENT" and e.value.option == option
    # what the C field holds goes to the library as it is, whether it takes it or not
    for options in ({"visibility": {"rays": 2 ** 24 + 1}}, {"visibility": {"min_samples": 65537}},
                    {"policy": -1}, {"policy": 2 ** 31 - 1}, {"up": (0, 0, float("nan"))},
                    {"evidence": {"sigma": float("inf")}}, {"weld_tolerance": float("nan")}):
        with pytest.raises(meshfix.MeshfixError) as e:
            meshfix.orient(indices, positions, **options)
        assert e.value.option is None and str(e.value) == "MESHFIX_ERROR_INVALID_ARGUMENT: " + text
    with pytest.raises(meshfix.MeshfixError) as e:
        meshfix.weld(positions, float("nan"))
    assert e.value.option is None and e.value.name == "MESHFIX_ERROR_INVALID_ARGUMENT"
    for options in ({"visibility": {"rays": 2 ** 24, "min_samples": np.uint32(65536), "flags": True}},
                    {"seed": 2 ** 32 - 1, "policy": np.int64(5)}, {"seed": np.uint64(7), "up": np.array([0, 0, 2])},
                    {"evidence": {"sigma": 1, "min_confidence": np.float64(0.5)}, "weld_tolerance": 1e-45}):
        assert meshfix.orient(indices, positions, **options)[1].triangles_flipped == 1
    rays = meshfix.orient(indices, positions, policy="visibility", visibility={"rays": 1000})[1].evidence.rays_cast
    assert rays == 1000


def test_sdf_policy_calls_python():
    """A unit cube with half its faces turned, by the SDF of a box: outward."""
    mesh = load("cube.ply")
    positions = mesh["positions"]
    centre = (positions.min(0) + positions.max(0)) / 2
    half = (positions.max(0) - positions.min(0)) / 2

    def box(p):
        q = np.abs(np.array(p) - centre) - half
        return float(np.linalg.norm(np.maximum(q, 0)) + min(q.max(), 0))

    indices = scramble(mesh["indices"], share=0.5)
    fixed, report = meshfix.orient(indices, positions, policy="sdf", sdf={"distance": box})
    assert report.evidence.sdf_evaluations > 0
    assert meshfix.check(fixed, positions, "solid"), meshfix.check(fixed, positions, "solid").text
    per_triangle = meshfix.orient(indices, positions, policy="sdf",
                                  sdf={"distance": box, "gradient": lambda p: (np.array(p) - centre).tolist(),
                                       "mode": "per_triangle"})
    assert meshfix.check(per_triangle[0], positions, "solid")

    def broken(p):
        raise RuntimeError("from the SDF")

    with pytest.raises(RuntimeError, match="from the SDF"):
        meshfix.orient(indices, positions, policy="sdf", sdf={"distance": broken})


def test_scratch_memory():
    mesh = load("spider.obj")
    size = meshfix.scratch_size(mesh["indices"].size, len(mesh["positions"]))
    assert size > 0
    plain = meshfix.orient(scramble(mesh["indices"]), mesh["positions"])
    scratch = np.zeros(size, np.uint8)
    given = meshfix.orient(scramble(mesh["indices"]), mesh["positions"], memory={"scratch": scratch})
    assert np.array_equal(plain[0], given[0])
    assert scratch.any(), "the call used the caller's scratch"
    with pytest.raises(meshfix.MeshfixError) as e:
        meshfix.orient(mesh["indices"], mesh["positions"], memory={"scratch": bytearray(64)})
    assert e.value.name == "MESHFIX_ERROR_SCRATCH_TOO_SMALL"


def test_errors_and_conversions():
    indices, positions = tetrahedron()
    with pytest.raises(meshfix.MeshfixError) as e:
        meshfix.orient(np.array([0, 1, 9], np.uint32), positions)
    assert e.value.name == "MESHFIX_ERROR_INDEX_OUT_OF_RANGE" and "not less than vertex_count" in str(e.value)
    with pytest.raises(meshfix.MeshfixError) as e:
        meshfix.orient(np.array([0, 1, 2, 3], np.uint32), positions)
    assert e.value.name == "MESHFIX_ERROR_NOT_TRIANGLES"
    with pytest.raises(meshfix.MeshfixError) as e:
        meshfix.orient(indices, None, policy="outward")
    assert e.value.name == "MESHFIX_ERROR_POSITIONS_REQUIRED"
    with pytest.raises(meshfix.MeshfixError) as e:
        meshfix.weld(np.array([[0, 0, np.nan]], np.float32))
    assert e.value.name == "MESHFIX_ERROR_NON_FINITE"
    # NumPy's default int64 and Python lists: converted, given back as given
    fixed, report = meshfix.orient(indices.astype(np.int64), positions.tolist())
    assert fixed.dtype == np.int64 and report.triangles_flipped == 1
    flat_fixed, _ = meshfix.orient(indices.reshape(-1), positions.reshape(-1))
    assert flat_fixed.shape == (12,) and flat_fixed.tolist() == fixed.reshape(-1).tolist()
    # big-endian, reversed and sliced arrays: copied into what C takes
    for p in (positions.astype(">f4"), positions.astype(">f8"), positions[::-1][::-1],
              np.hstack([positions, positions])[:, 3:]):
        again, r = meshfix.orient(indices.astype(">u4"), p)
        assert again.tolist() == fixed.tolist() and r.triangles_flipped == 1
    with pytest.raises(meshfix.MeshfixError):
        meshfix.orient(np.array([0, -1, 2]), positions)
    with pytest.raises(TypeError):
        meshfix.orient(indices.astype(np.float32), positions)
    empty, report = meshfix.orient(np.zeros(0, np.uint32), positions)
    assert empty.size == 0 and report.verdict == meshfix.Verdict.CLEAN
    check = meshfix.check(indices, positions, ["consistent", "closed"])
    assert not check and check.requirement == meshfix.Requirement.CONSISTENT and check.triangle == 0


def test_normals_policy_needs_positions_and_normals():
    indices, positions = tetrahedron()
    normals = np.cross(positions[indices[:, 1]] - positions[indices[:, 0]],
                       positions[indices[:, 2]] - positions[indices[:, 0]])
    texts = dict(header_list("MESHFIX_RESULT_LIST"))
    for given, evidence, name in ((None, {"triangle_normals": normals}, "MESHFIX_ERROR_POSITIONS_REQUIRED"),
                                  (positions, {}, "MESHFIX_ERROR_NORMALS_REQUIRED")):
        with pytest.raises(meshfix.MeshfixError) as e:
            meshfix.orient(indices, given, policy="normals", evidence=evidence)
        assert e.value.name == name and str(e.value) == "%s: %s" % (name, texts[name])
    fixed, report = meshfix.orient(indices, positions, policy="normals", evidence={"triangle_normals": -normals})
    assert report.triangles_flipped == 3 and report.evidence.patches_by_normals == 1


def test_many_components_all_reported():
    """More components than the first call makes room for (a soup of 300
    triangles): the binding calls again with room for all."""
    rng = np.random.default_rng(1)
    positions = rng.random((900, 3)).astype(np.float32)
    indices = np.arange(900, dtype=np.uint32).reshape(-1, 3)
    report, out = meshfix.inspect(indices, positions, outputs=["components"])
    assert report.mesh.components == 300 and len(out.components) == 300
    assert (out.components["triangles"] == 1).all()
    assert out.patch_ids is None


def test_orient_is_idempotent_on_every_model():
    for name in MODEL_NAMES:
        path = models.MODELS[name]
        if not os.path.exists(path):
            continue
        mesh = models.load(name)
        fixed, _ = meshfix.orient(scramble(mesh["indices"]), mesh["positions"])
        again, report = meshfix.orient(fixed, mesh["positions"])
        assert report.triangles_flipped == 0 and np.array_equal(fixed, again), name
