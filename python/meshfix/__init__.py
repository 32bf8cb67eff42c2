"""meshfix: find and repair triangle winding, on NumPy arrays.

A thin binding (ctypes) over meshfix.h's C API, built into a shared library
next to this file (python/build.sh, or pip). The arrays go to C as they are:
uint16 or uint32 indices become the C API's index_size 2 or 4, float32 or
float64 positions its position_size 4 or 8, and a (vertex_count, k) array
whose rows hold x y z first (an engine's interleaved vertex buffer) its
stride, so nothing is copied unless a dtype or layout has no C counterpart.

    import numpy as np, meshfix
    positions = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], np.float32)
    indices = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 3, 2]], np.uint32)
    fixed, report = meshfix.orient(indices, positions)
    report.triangles_flipped   # 1
    report.summary             # 'fixed 1 triangle in 1 patch'
    fixed[3]                   # array([1, 2, 3], dtype=uint32)

Functions (keyword options as in C's meshfix_options, below):
    orient(indices, positions=None, *, outputs=False, **options)
        -> (new_indices, Report) or (new_indices, Report, Outputs)
    inspect(indices, positions=None, *, outputs=False, **options)
        -> Report or (Report, Outputs)
    check(indices, positions=None, requirements="consistent", **options) -> Check
    weld(positions, tolerance=0.0, **options) -> (remap, unique_count)
    scratch_size(index_count, vertex_count, **options) -> int

Options (all optional; the C defaults when left out):
    policy="auto" | "seed" | "majority" | "outward" | "sdf" | "visibility"
           | "up" | "normals"                (or a Policy, or its int)
    topology="positions" | "indices" | "weld", weld_tolerance=0.0,
    up=(x, y, z), seed=0,
    evidence=dict(sigma=, min_confidence=, triangle_normals=(T, 3) array,
                  vertex_normals=(V, 3) array),
    visibility=dict(rays=, min_samples=, coherence_distance=, c0=, eps=,
                    kv=, flags=),
    sdf=dict(distance=f(p) -> float, gradient=g(p) -> (gx, gy, gz),
             step=, mode="per_patch" | "per_triangle"),
    memory=dict(scratch=writable buffer of scratch_size() bytes),
    threads=N: options.parallel_for runs the ray batches on N threads
               (the result is the same, bit for bit).
memory.alloc_func/free_func are not exposed: the library uses malloc.

Errors from C raise MeshfixError (.result, .name, the C text); a mesh that
fails check() is not an error: check() returns a false Check with the
reason in .text. A value its C field cannot hold (an integer out of the
field's range or not whole, a finite number beyond float's) is refused
before the call, from check() too: MeshfixError with the library's
MESHFIX_ERROR_INVALID_ARGUMENT and .option naming it. Values the field
holds (NaN, rays above the library's limit) go to C for it to judge.
"""

import collections
import ctypes
import dataclasses
import enum
import glob
import math
import operator
import os
import sys
from ctypes import (CFUNCTYPE, POINTER, Structure, c_char, c_char_p, c_double, c_float, c_int, c_long,
                    c_size_t, c_uint, c_void_p)

import numpy as np

__all__ = ["orient", "inspect", "check", "weld", "scratch_size", "summary", "Report", "MeshFacts",
           "EvidenceCounts", "Outputs", "Check", "MeshfixError", "Policy", "Topology", "SdfMode", "Verdict", "Evidence",
           "Requirement", "VISIBILITY_COHERENCE_ONLY", "VISIBILITY_ONLY", "PolicyInfo", "policy_info", "doubtful_below",
           "version", "__version__"]

# ---- the shared library ----


def _find_library():
    here = os.path.dirname(os.path.abspath(__file__))
    explicit = os.environ.get("MESHFIX_LIBRARY")
    if explicit:
        return explicit
    for pattern in ("_libmeshfix*.so", "_libmeshfix*.dylib", "_libmeshfix*.pyd", "_libmeshfix*.dll"):
        found = sorted(glob.glob(os.path.join(here, pattern)))
        if found:
            return found[0]
    raise ImportError("meshfix: no _libmeshfix shared library next to %s; build it with python/build.sh "
                      "(or pip install ./python), or set MESHFIX_LIBRARY" % __file__)


_lib = ctypes.CDLL(_find_library())

# ---- the C structs, field for field (checked against the library at import) ----

_TASK = CFUNCTYPE(None, c_void_p, c_size_t)
_PARALLEL_FOR = CFUNCTYPE(None, _TASK, c_void_p, c_size_t, c_void_p)
_SDF_DISTANCE = CFUNCTYPE(c_float, POINTER(c_float), c_void_p)
_SDF_GRADIENT = CFUNCTYPE(None, POINTER(c_float), POINTER(c_float), c_void_p)


class _MemoryOptions(Structure):
    _fields_ = [("alloc_func", c_void_p), ("free_func", c_void_p), ("user_data", c_void_p),
                ("scratch", c_void_p), ("scratch_size", c_size_t)]


class _EvidenceOptions(Structure):
    _fields_ = [("sigma", c_float), ("min_confidence", c_float),
                ("triangle_normals", c_void_p), ("triangle_normals_stride", c_size_t),
                ("vertex_normals", c_void_p), ("vertex_normals_stride", c_size_t)]


class _VisibilityOptions(Structure):
    _fields_ = [("rays", c_size_t), ("min_samples", c_uint), ("coherence_distance", c_float),
                ("c0", c_float), ("eps", c_float), ("kv", c_float), ("flags", c_uint)]


class _SdfOptions(Structure):
    _fields_ = [("distance", _SDF_DISTANCE), ("gradient", _SDF_GRADIENT), ("user", c_void_p),
                ("step", c_float), ("mode", c_int)]


class _Options(Structure):
    _fields_ = [("index_size", c_uint), ("position_size", c_uint), ("topology", c_int),
                ("weld_tolerance", c_float), ("policy", c_int), ("up", c_float * 3), ("seed", c_uint),
                ("evidence", _EvidenceOptions), ("visibility", _VisibilityOptions), ("sdf", _SdfOptions),
                ("memory", _MemoryOptions), ("parallel_for", _PARALLEL_FOR), ("parallel_user", c_void_p)]


class _Component(Structure):
    _fields_ = [("first_triangle", c_size_t), ("triangles", c_size_t), ("vertices", c_size_t),
                ("edges", c_size_t), ("edges_boundary", c_size_t), ("edges_non_manifold", c_size_t),
                ("patches", c_size_t), ("euler_characteristic", c_long), ("closed", c_int),
                ("orientable", c_int), ("area", c_double), ("signed_volume", c_double)]


class _Outputs(Structure):
    _fields_ = [("flipped", c_void_p), ("patch_ids", c_void_p), ("patch_confidence", c_void_p),
                ("patch_confidence_capacity", c_size_t), ("components", c_void_p),
                ("components_capacity", c_size_t), ("patch_evidence", c_void_p),
                ("patch_evidence_capacity", c_size_t)]


class _MeshFacts(Structure):
    _fields_ = [(name, c_size_t) for name in (
        "triangles", "triangles_degenerate", "triangles_zero_area", "triangles_duplicate", "vertices_used",
        "vertices_joined", "vertices_non_finite", "vertices_non_manifold", "edges", "edges_boundary",
        "edges_manifold", "edges_non_manifold", "edges_inconsistent", "patches", "patches_closed",
        "patches_inside_out", "components", "components_closed", "components_non_orientable")] + [
        ("euler_characteristic", c_long), ("area", c_double), ("signed_volume", c_double)]


class _EvidenceCounts(Structure):
    _fields_ = [(name, c_size_t) for name in (
        "patches_by_volume", "patches_by_parity", "patches_by_visibility", "patches_by_normals", "patches_kept",
        "shells_inward", "rays_cast", "patch_pairs", "patches_merged", "pairs_conflicting", "sdf_evaluations",
        "triangles_sdf_disagree", "triangles_against_normals")]


class _Report(Structure):
    _fields_ = [("verdict", c_int), ("triangles_flipped", c_size_t), ("patches_flipped", c_size_t),
                ("patches_doubtful", c_size_t), ("triangles_doubtful", c_size_t), ("area_doubtful", c_double),
                ("edges_inconsistent_before", c_size_t), ("verdict_before", c_int),
                ("patches_inside_out_before", c_size_t), ("signed_volume_before", c_double), ("mesh", _MeshFacts),
                ("evidence", _EvidenceCounts)]


class _CheckFailure(Structure):
    _fields_ = [("result", c_int), ("requirement", c_uint), ("count", c_size_t), ("triangle", c_size_t),
                ("edge", c_uint * 2), ("text", c_char * 200)]


class _PolicyFacts(Structure):
    _fields_ = [("name", c_char_p), ("description", c_char_p), ("needs_positions", c_int),
                ("needs_normals", c_int), ("needs_distance", c_int), ("reads_up", c_int), ("casts_rays", c_int)]


_C_NAMES = {
    _MemoryOptions: "meshfix_memory_options", _EvidenceOptions: "meshfix_evidence_options",
    _VisibilityOptions: "meshfix_visibility_options", _SdfOptions: "meshfix_sdf_options",
    _Options: "meshfix_options", _Component: "meshfix_component", _Outputs: "meshfix_outputs",
    _MeshFacts: "meshfix_mesh_facts", _EvidenceCounts: "meshfix_evidence_counts", _Report: "meshfix_report",
    _CheckFailure: "meshfix_check_failure", _PolicyFacts: "meshfix_policy_facts",
}


def _check_layout():
    """The library's own account of its structs must match the ctypes mirror."""
    _lib.meshfix_python_layout.restype = c_size_t
    _lib.meshfix_python_layout.argtypes = [c_char_p, c_size_t]
    size = _lib.meshfix_python_layout(None, 0) + 1
    buffer = ctypes.create_string_buffer(size)
    _lib.meshfix_python_layout(buffer, size)
    c_side, version = {}, None
    for line in buffer.value.decode().splitlines():
        words = line.split()
        if words[0] == "version":
            version = tuple(int(w) for w in words[1:])
        else:
            c_side[(words[0], words[1])] = (int(words[2]), int(words[3]))
    py_side = {}
    for struct, name in _C_NAMES.items():
        py_side[(name, "-")] = (0, ctypes.sizeof(struct))
        for field, _ in struct._fields_:
            descriptor = getattr(struct, field)
            py_side[(name, field)] = (descriptor.offset, descriptor.size)
    if c_side != py_side:
        differ = sorted(k for k in set(c_side) | set(py_side) if c_side.get(k) != py_side.get(k))
        raise ImportError("meshfix: the library's structs differ from this module's mirror (%s); this "
                          "module does not match meshfix.h %s" % (", ".join(" ".join(k) for k in differ[:8]),
                                                                 ".".join(map(str, version))))
    return version


_VERSION = _check_layout()
version = _VERSION
__version__ = "%d.%d.%d" % _VERSION


def _declare(name, restype, argtypes):
    function = getattr(_lib, name)
    function.restype = restype
    function.argtypes = argtypes
    return function


_orient = _declare("meshfix_orient", c_int, [c_void_p, c_void_p, c_size_t, c_void_p, c_size_t, c_size_t,
                                             POINTER(_Options), POINTER(_Report), POINTER(_Outputs)])
_inspect = _declare("meshfix_inspect", c_int, [c_void_p, c_size_t, c_void_p, c_size_t, c_size_t,
                                               POINTER(_Options), POINTER(_Report), POINTER(_Outputs)])
_check = _declare("meshfix_check", c_int, [c_void_p, c_size_t, c_void_p, c_size_t, c_size_t, c_uint,
                                           POINTER(_Options), POINTER(_CheckFailure)])
_summary = _declare("meshfix_summary", c_size_t, [POINTER(_Report), c_char_p, c_size_t])
_weld = _declare("meshfix_weld", c_int, [c_void_p, c_void_p, c_size_t, c_size_t, c_float, POINTER(_Options),
                                         POINTER(c_size_t)])
_scratch_size = _declare("meshfix_scratch_size", c_size_t, [c_size_t, c_size_t, POINTER(_Options)])
_result_string = _declare("meshfix_result_string", c_char_p, [c_int])
_verdict_string = _declare("meshfix_verdict_string", c_char_p, [c_int])
_result_name = _declare("meshfix_python_result_name", c_char_p, [c_int])
_policy_string = _declare("meshfix_policy_string", c_char_p, [c_int])
_policy_from_string = _declare("meshfix_policy_from_string", c_int, [c_char_p])
_policy_info = _declare("meshfix_policy_info", POINTER(_PolicyFacts), [c_int])
_doubtful_below = _declare("meshfix_doubtful_below", c_float, [POINTER(_Options), c_int])
_verdict_worst = _declare("meshfix_verdict_worst", c_int, [c_int, c_int])

# ---- enums ----


def _member(name):
    """A name as an enum member's: "per triangle", "Per-Triangle" -> PER_TRIANGLE."""
    return name.strip().upper().replace(" ", "_").replace("-", "_")


def _policies():
    """(member name, value) of each policy: the header's names (meshfix_policy_string), the one table
    of them; their count is what meshfix_policy_from_string answers for a name that is none."""
    return [(_member(_policy_string(i).decode()), i) for i in range(_policy_from_string(None))]


Policy = enum.IntEnum("Policy", _policies(), module=__name__)
Policy.__doc__ = "meshfix_policy: AUTO, SEED, ..., NORMALS, named as the library names them."


class Topology(enum.IntEnum):
    POSITIONS = 0
    INDICES = 1
    WELD = 2


class SdfMode(enum.IntEnum):
    PER_PATCH = 0
    PER_TRIANGLE = 1


class Verdict(enum.IntEnum):
    CLEAN = 0
    REPAIRED = 1
    DOUBTFUL = 2
    NOT_ORIENTABLE = 3
    INCONSISTENT = 4
    INSIDE_OUT = 5

    def __str__(self):
        return _verdict_string(int(self)).decode()


class Evidence(enum.IntEnum):
    """What decided a patch (meshfix_evidence; Outputs.patch_evidence)."""
    NONE = 0
    VOLUME = 1
    PARITY = 2
    VISIBILITY = 3
    NORMALS = 4
    POLICY = 5


class Requirement(enum.IntFlag):
    CONSISTENT = 1
    CLOSED = 2
    MANIFOLD = 4
    OUTWARD = 8
    NO_DEGENERATE = 16
    SOLID = 31


VISIBILITY_COHERENCE_ONLY = 1
VISIBILITY_ONLY = 2


def _result_names():
    """The result codes' names, MESHFIX_OK first: the header's MESHFIX_RESULT_LIST as the library has
    it, so a code added there is named here without a copy of the list to fall behind."""
    names = []
    while _result_name(len(names)) is not None:
        names.append(_result_name(len(names)).decode())
    return names


_RESULT_NAMES = _result_names()
_RESULT_CODES = {name: code for code, name in enumerate(_RESULT_NAMES)}


def _result_name_of(result, unknown):
    return _RESULT_NAMES[result] if 0 <= result < len(_RESULT_NAMES) else unknown


class MeshfixError(Exception):
    """A meshfix_result other than MESHFIX_OK: .result (int), .name, and the C text as the message.

    .option names the option (or argument) the binding refused before the call because its C field
    cannot hold the value, with the result the library gives an option out of range; None when the
    library itself refused."""

    def __init__(self, result, option=None, why=None):
        self.result = int(result)
        self.name = _result_name_of(self.result, "MESHFIX_ERROR")
        self.option = option
        message = "%s: %s" % (self.name, _result_string(self.result).decode())
        super().__init__(message if option is None else "%s (%s %s)" % (message, option, why))


def _enum(kind, value, what):
    """A member's name to its value; any other value as given: the C field it is set in checks it (_set)."""
    if isinstance(value, str):
        try:
            return kind[_member(value)]
        except KeyError:
            raise ValueError("meshfix: unknown %s %r (one of %s)" % (
                what, value, ", ".join(m.name.lower() for m in kind))) from None
    return value


_C_TYPE_NAMES = {c_size_t: "size_t", c_uint: "unsigned int", c_int: "int", c_float: "float"}


def _refused(what, value, why):
    """The library's MESHFIX_ERROR_INVALID_ARGUMENT (an option out of range), naming the one refused."""
    return MeshfixError(_RESULT_CODES["MESHFIX_ERROR_INVALID_ARGUMENT"], what, "= %r %s" % (value, why))


def _c_value(ctype, value, what):
    """value as a C `ctype` holds it, or refused where ctypes would change it silently: an integer
    wrapped to the field's width or cut from a float, a finite number beyond float's range made
    infinite. NaN and infinity are floats: they go as they are, for the library to take or refuse."""
    if ctype is c_float:
        try:
            x = float(value) if hasattr(value, "__float__") else None  # float() would parse a string
        except OverflowError:  # an integer beyond any double
            raise _refused(what, value, "does not fit a float") from None
        if x is None:
            raise _refused(what, value, "is not a number")
        if math.isfinite(x) and not math.isfinite(c_float(x).value):
            raise _refused(what, value, "does not fit a float")
        return x
    try:
        n = operator.index(value)
    except TypeError:
        raise _refused(what, value, "is not an integer (%s)" % _C_TYPE_NAMES[ctype]) from None
    if ctype(n).value != n:
        raise _refused(what, value, "does not fit %s" % _C_TYPE_NAMES[ctype])
    return n


def _set(struct, field, value, what):
    """struct.field = value, checked against the field's C type (_c_value)."""
    setattr(struct, field, _c_value(dict(struct._fields_)[field], value, what))


# ---- the report, as dataclasses built from the C structs' fields ----

def _plain(ctype):
    return {c_double: float, c_float: float}.get(ctype, int)


MeshFacts = dataclasses.make_dataclass("MeshFacts", [(name, _plain(t)) for name, t in _MeshFacts._fields_])
MeshFacts.__module__ = __name__
MeshFacts.__doc__ = "What the mesh is (orient: as returned; inspect: as given): meshfix_mesh_facts."
EvidenceCounts = dataclasses.make_dataclass("EvidenceCounts",
                                            [(name, _plain(t)) for name, t in _EvidenceCounts._fields_])
EvidenceCounts.__module__ = __name__
EvidenceCounts.__doc__ = "What decided the patches (orient): meshfix_evidence_counts."


@dataclasses.dataclass
class Report:
    """meshfix_report, with the verdict as a Verdict and meshfix_summary's line as .summary."""
    verdict: Verdict
    summary: str
    triangles_flipped: int
    patches_flipped: int
    patches_doubtful: int
    triangles_doubtful: int
    area_doubtful: float
    edges_inconsistent_before: int  # the mesh as given: what inspect reports of it
    verdict_before: Verdict
    patches_inside_out_before: int
    signed_volume_before: float
    mesh: MeshFacts
    evidence: EvidenceCounts

    def to_dict(self):
        """Plain types only (the verdicts as their C text, e.g. "repaired"), for JSON."""
        d = dataclasses.asdict(self)
        d["verdict"] = str(self.verdict)
        d["verdict_before"] = str(self.verdict_before)
        return d


def _fields(struct, kind):
    return kind(**{name: getattr(struct, name) for name, _ in struct._fields_})


def _verdict(value):
    try:
        return Verdict(value)
    except ValueError:
        return value


def _report(c_report):
    size = _summary(ctypes.byref(c_report), None, 0) + 1
    line = ctypes.create_string_buffer(size)
    _summary(ctypes.byref(c_report), line, size)
    return Report(verdict=_verdict(c_report.verdict), summary=line.value.decode(),
                  triangles_flipped=c_report.triangles_flipped, patches_flipped=c_report.patches_flipped,
                  patches_doubtful=c_report.patches_doubtful, triangles_doubtful=c_report.triangles_doubtful,
                  area_doubtful=c_report.area_doubtful, edges_inconsistent_before=c_report.edges_inconsistent_before,
                  verdict_before=_verdict(c_report.verdict_before),
                  patches_inside_out_before=c_report.patches_inside_out_before,
                  signed_volume_before=c_report.signed_volume_before,
                  mesh=_fields(c_report.mesh, MeshFacts), evidence=_fields(c_report.evidence, EvidenceCounts))


def summary(report):
    """The report's line in plain words (meshfix_summary): the same as report.summary."""
    return report.summary


@dataclasses.dataclass
class Outputs:
    """meshfix_outputs as arrays (None when not asked for).

    flipped: bool per triangle (orient); patch_ids: uint32 per triangle
    (0xFFFFFFFF: degenerate); patch_confidence: float32 per patch (orient);
    patch_evidence: uint8 per patch, what decided it (an Evidence, orient);
    components: a structured array with meshfix_component's fields."""
    flipped: object = None
    patch_ids: object = None
    patch_confidence: object = None
    components: object = None
    patch_evidence: object = None


@dataclasses.dataclass
class Check:
    """meshfix_check's answer; true when every requirement holds.

    requirement: the Requirement that failed first (0 when all hold);
    count, triangle (None: none) and edge (None: none) say where;
    text: the one-line reason; result: the MESHFIX_* name when the mesh was
    not valid input at all."""
    ok: bool
    requirement: int
    count: int
    triangle: object
    edge: object
    text: str
    result: str

    def __bool__(self):
        return self.ok


# ---- arrays in ----

def _indices(indices):
    """(array for C, index_size, shape and dtype to give back)."""
    a = np.asarray(indices)
    if a.dtype == np.uint16 or a.dtype == np.uint32:
        pass  # as they are: index_size 2 or 4
    elif a.dtype.kind in "iu":  # int64 (NumPy's default), int32, ...: a checked copy
        if a.size and (a.min() < 0 or a.max() > 0xFFFFFFFF):
            raise MeshfixError(_RESULT_CODES["MESHFIX_ERROR_INDEX_OUT_OF_RANGE"])
        a = a.astype(np.uint32)
    else:
        raise TypeError("meshfix: indices must be an integer array (uint16 or uint32 go to C as they are), "
                        "not %s" % a.dtype)
    if a.ndim > 2 or (a.ndim == 2 and a.shape[1] != 3):
        raise ValueError("meshfix: indices must be flat or (triangles, 3), not %s" % (a.shape,))
    c = np.require(a, requirements=["C", "A"]).reshape(-1)
    return c, c.dtype.itemsize, np.asarray(indices).shape, np.asarray(indices).dtype


def _positions(positions):
    """(array kept alive, vertex_count, stride in bytes, position_size)."""
    if positions is None:
        return None, 0, 0, 4
    a = np.asarray(positions)
    if a.dtype.kind == "f" and a.dtype.itemsize in (4, 8) and not a.dtype.isnative:
        a = a.astype(a.dtype.newbyteorder("="))
    if a.dtype != np.float32 and a.dtype != np.float64:
        if a.dtype.kind not in "iuf":
            raise TypeError("meshfix: positions must be float32 or float64 (or numbers), not %s" % a.dtype)
        a = a.astype(np.float32 if a.dtype == np.float16 else np.float64)
    if a.ndim == 1:
        if a.size % 3:
            raise ValueError("meshfix: flat positions must hold x y z triples (%d values)" % a.size)
        a = a.reshape(-1, 3)
    if a.ndim != 2 or a.shape[1] < 3:
        raise ValueError("meshfix: positions must be (vertices, 3) or (vertices, k >= 3) with x y z first, "
                         "not %s" % (a.shape,))
    item = a.itemsize
    # rows of x y z first, `stride` bytes apart: an interleaved vertex buffer goes as it is
    if not (a.strides[1] == item and a.strides[0] >= 3 * item and a.strides[0] % item == 0 and
            a.flags.aligned) or a.shape[0] == 0:
        a = np.ascontiguousarray(a[:, :3])
    stride = a.strides[0] if a.shape[0] > 1 else 3 * item
    return a, a.shape[0], stride, item


def _normals(normals, what, rows):
    """(array kept alive, stride in bytes); rows: (how many C reads, of what), None: C reads none."""
    if normals is None:
        return None, 0
    a = np.asarray(normals)
    if a.dtype != np.float32:  # the C API takes float normals (also from double positions)
        a = a.astype(np.float32)
    if a.ndim == 1:
        a = a.reshape(-1, 3)
    if a.ndim != 2 or a.shape[1] < 3:
        raise ValueError("meshfix: %s must be (n, 3) or (n, k >= 3), not %s" % (what, a.shape))
    # C takes a pointer, not a length: it reads `rows` normals whatever the array holds
    if rows is not None and a.shape[0] != rows[0]:
        raise ValueError("meshfix: %s has %d row%s; the %d %s need %d (one each)" % (
            what, a.shape[0], "" if a.shape[0] == 1 else "s", rows[0], rows[1], rows[0]))
    if not (a.strides[1] == 4 and a.strides[0] >= 12 and a.strides[0] % 4 == 0 and a.flags.aligned):
        a = np.ascontiguousarray(a[:, :3])
    return a, a.strides[0]


def _pointer(a):
    return None if a is None else a.ctypes.data_as(c_void_p)


class _Call:
    """meshfix_options filled from keywords, and everything C will point at, kept alive."""

    _GROUPS = {
        "evidence": ("sigma", "min_confidence", "triangle_normals", "vertex_normals"),
        "visibility": ("rays", "min_samples", "coherence_distance", "c0", "eps", "kv", "flags"),
        "sdf": ("distance", "gradient", "step", "mode"),
        "memory": ("scratch",),
    }

    def __init__(self, sizes, counts, policy=None, topology=None, weld_tolerance=0.0, up=None, seed=0,
                 evidence=None, visibility=None, sdf=None, memory=None, threads=None):
        """sizes: (index_size, position_size); counts: (index_count, vertex_count) of the call, the
        normals' rows, or None for a call that reads no normals. Positional, so no keyword sets them."""
        o = self.options = _Options()
        self.keep = []
        self.error = None
        o.index_size, o.position_size = sizes
        if policy is not None:
            _set(o, "policy", _enum(Policy, policy, "policy"), "policy")
        if topology is not None:
            _set(o, "topology", _enum(Topology, topology, "topology"), "topology")
        _set(o, "weld_tolerance", weld_tolerance, "weld_tolerance")
        if up is not None:
            up = list(up)
            if len(up) != 3:
                raise ValueError("meshfix: up must be three numbers")
            o.up[:] = [_c_value(c_float, x, "up[%d]" % i) for i, x in enumerate(up)]
        _set(o, "seed", seed, "seed")
        for group, given in (("evidence", evidence), ("visibility", visibility), ("sdf", sdf),
                             ("memory", memory)):
            unknown = set(given or {}) - set(self._GROUPS[group])
            if unknown:
                raise TypeError("meshfix: unknown %s option(s) %s (known: %s)" % (
                    group, ", ".join(sorted(unknown)), ", ".join(self._GROUPS[group])))
        evidence = evidence or {}
        for name in ("sigma", "min_confidence"):
            _set(o.evidence, name, evidence.get(name, 0.0), "evidence." + name)
        rows = (None, None) if counts is None else ((counts[0] // 3, "triangles"), (counts[1], "vertices"))
        for name, need in zip(("triangle_normals", "vertex_normals"), rows):
            array, stride = _normals(evidence.get(name), name, need)
            self.keep.append(array)
            setattr(o.evidence, name, _pointer(array))
            setattr(o.evidence, name + "_stride", stride)
        visibility = visibility or {}
        for name, _ in _VisibilityOptions._fields_:
            if name in visibility:
                _set(o.visibility, name, visibility[name], "visibility." + name)
        if sdf:
            self._sdf(o.sdf, sdf)
        if memory and memory.get("scratch") is not None:
            buffer = memory["scratch"]
            view = np.frombuffer(buffer, dtype=np.uint8)  # raises for a read-only buffer below
            if not view.flags.writeable:
                raise ValueError("meshfix: memory scratch must be writable")
            self.keep.append((buffer, view))
            o.memory.scratch = view.ctypes.data_as(c_void_p)
            o.memory.scratch_size = view.nbytes
        if threads is not None and int(threads) > 1:
            self._parallel(o, int(threads))

    def _sdf(self, s, sdf):
        distance, gradient = sdf.get("distance"), sdf.get("gradient")

        def call_distance(p, _user):
            try:
                return float(distance((p[0], p[1], p[2])))
            except BaseException as e:  # reported after the C call returns
                self.error = self.error or e
                return 0.0

        def call_gradient(p, g, _user):
            try:
                v = gradient((p[0], p[1], p[2]))
                g[0], g[1], g[2] = float(v[0]), float(v[1]), float(v[2])
            except BaseException as e:
                self.error = self.error or e
                g[0] = g[1] = g[2] = 0.0

        if distance is not None:
            s.distance = _SDF_DISTANCE(call_distance)
            self.keep.append(s.distance)
        if gradient is not None:
            s.gradient = _SDF_GRADIENT(call_gradient)
            self.keep.append(s.gradient)
        _set(s, "step", sdf.get("step", 0.0), "sdf.step")
        _set(s, "mode", _enum(SdfMode, sdf.get("mode", 0), "sdf mode"), "sdf.mode")

    def _parallel(self, o, threads):
        from concurrent.futures import ThreadPoolExecutor
        pool = ThreadPoolExecutor(max_workers=threads)
        self.pool = pool

        def run(task, context, lo, hi):
            for i in range(lo, hi):
                task(context, i)  # a call into C: ctypes lets go of the GIL

        def parallel_for(task, context, count, _user):
            # C reads what the tasks wrote once this returns, and frees the memory they write: so
            # whatever goes wrong (the pool refuses a chunk, Ctrl-C while waiting), every task has
            # run and none is running when it returns; the error is raised after C returns
            chunk = max(1, count // (4 * threads))
            jobs = []
            for lo in range(0, count, chunk):
                try:
                    jobs.append(pool.submit(run, task, context, lo, min(count, lo + chunk)))
                except BaseException as e:
                    self.error = self.error or e
                    run(task, context, lo, min(count, lo + chunk))
            for job in jobs:
                while True:
                    try:
                        job.result()
                        break
                    except BaseException as e:
                        self.error = self.error or e
                        if job.done():
                            break

        o.parallel_for = _PARALLEL_FOR(parallel_for)
        self.keep.append(o.parallel_for)

    def done(self, result):
        if getattr(self, "pool", None) is not None:
            self.pool.shutdown()
        if self.error is not None:
            raise self.error
        if result != 0:
            raise MeshfixError(result)


def _outputs_wanted(outputs, allowed):
    if outputs is True:
        return set(allowed)
    if not outputs:
        return set()
    wanted = {outputs} if isinstance(outputs, str) else set(outputs)
    unknown = wanted - set(allowed)
    if unknown:
        raise ValueError("meshfix: unknown output(s) %s (known here: %s)" % (", ".join(sorted(unknown)),
                                                                          ", ".join(allowed)))
    return wanted


_COMPONENT_DTYPE = np.dtype({"names": [n for n, _ in _Component._fields_],
                             "formats": [np.dtype(t) for _, t in _Component._fields_],
                             "offsets": [getattr(_Component, n).offset for n, _ in _Component._fields_],
                             "itemsize": ctypes.sizeof(_Component)})


class _OutputArrays:
    def __init__(self, wanted, triangles, component_capacity):
        self.o = _Outputs()
        self.arrays = Outputs()
        if "flipped" in wanted:
            self.arrays.flipped = np.zeros(triangles, np.uint8)
            self.o.flipped = _pointer(self.arrays.flipped)
        if "patch_ids" in wanted:
            self.arrays.patch_ids = np.zeros(triangles, np.uint32)
            self.o.patch_ids = _pointer(self.arrays.patch_ids)
        if "patch_confidence" in wanted:  # at most one patch per triangle
            self.arrays.patch_confidence = np.zeros(triangles, np.float32)
            self.o.patch_confidence = _pointer(self.arrays.patch_confidence)
            self.o.patch_confidence_capacity = triangles
        if "patch_evidence" in wanted:
            self.arrays.patch_evidence = np.zeros(triangles, np.uint8)
            self.o.patch_evidence = _pointer(self.arrays.patch_evidence)
            self.o.patch_evidence_capacity = triangles
        if "components" in wanted:
            self.arrays.components = np.zeros(component_capacity, _COMPONENT_DTYPE)
            self.o.components = _pointer(self.arrays.components)
            self.o.components_capacity = component_capacity

    def result(self, report):
        a = self.arrays
        if a.flipped is not None:
            a.flipped = a.flipped.view(np.bool_)
        if a.patch_confidence is not None:
            a.patch_confidence = a.patch_confidence[:report.mesh.patches].copy()
        if a.patch_evidence is not None:
            a.patch_evidence = a.patch_evidence[:report.mesh.patches].copy()
        if a.components is not None:
            a.components = a.components[:report.mesh.components].copy()
        return a


# components are few on most meshes: a first call takes this many, and a
# call with more components than that is made again with room for all
_FIRST_COMPONENTS = 256


def _run(call_c, wanted, triangles):
    """Calls call_c(outputs pointer, report) with output arrays; again when components did not fit."""
    capacity = min(triangles, _FIRST_COMPONENTS)
    while True:
        out = _OutputArrays(wanted, triangles, capacity) if wanted else None
        report = _Report()
        call_c(ctypes.byref(out.o) if out else None, report)
        r = _report(report)
        if out is None or "components" not in wanted or r.mesh.components <= capacity:
            return r, (out.result(r) if out else None)
        capacity = r.mesh.components


def _mesh(indices, positions, options):
    idx, index_size, shape, dtype = _indices(indices)
    pos, vertex_count, stride, position_size = _positions(positions)
    if pos is None:
        vertex_count = int(idx.max()) + 1 if idx.size else 0
    call = _Call((index_size, position_size), (idx.size, vertex_count), **options)
    return idx, pos, vertex_count, stride, call, shape, dtype


def orient(indices, positions=None, *, outputs=False, **options):
    """Repair winding (meshfix_orient): returns (new_indices, report), or
    (new_indices, report, outputs) when outputs is True or names some of
    "flipped", "patch_ids", "patch_confidence", "patch_evidence", "components".

    new_indices has the shape and dtype of `indices`; a flipped triangle
    (a, b, c) is (a, c, b) in it. Without positions, vertex_count is the
    largest index + 1 and the policy must not need them."""
    idx, pos, vertex_count, stride, call, shape, dtype = _mesh(indices, positions, options)
    wanted = _outputs_wanted(outputs, ("flipped", "patch_ids", "patch_confidence", "patch_evidence", "components"))
    destination = np.empty_like(idx)
    triangles = idx.size // 3

    def call_c(out, report):
        result = _orient(_pointer(destination), _pointer(idx), idx.size, _pointer(pos), vertex_count, stride,
                         ctypes.byref(call.options), ctypes.byref(report), out)
        call.done(result)

    report, arrays = _run(call_c, wanted, triangles)
    fixed = destination
    if fixed.dtype != dtype:
        fixed = fixed.astype(dtype)
    fixed = fixed.reshape(shape)
    return (fixed, report, arrays) if wanted else (fixed, report)


def inspect(indices, positions=None, *, outputs=False, **options):
    """Report without changing anything (meshfix_inspect): a Report, or (report,
    outputs) when outputs is True or names "patch_ids" and/or "components"."""
    idx, pos, vertex_count, stride, call, _, _ = _mesh(indices, positions, options)
    wanted = _outputs_wanted(outputs, ("patch_ids", "components"))

    def call_c(out, report):
        result = _inspect(_pointer(idx), idx.size, _pointer(pos), vertex_count, stride,
                          ctypes.byref(call.options), ctypes.byref(report), out)
        call.done(result)

    report, arrays = _run(call_c, wanted, idx.size // 3)
    return (report, arrays) if wanted else report


def _requirements(requirements):
    if isinstance(requirements, str):
        requirements = requirements.replace("|", ",").replace("+", ",").split(",")
    if not isinstance(requirements, (list, tuple, set, frozenset)):
        requirements = [requirements]
    bits = 0
    for r in requirements:
        bits |= _c_value(c_uint, _enum(Requirement, r, "requirement"), "requirements")
    return bits


def check(indices, positions=None, requirements="consistent", **options):
    """One-line assertion (meshfix_check): a Check, true when the mesh is valid
    input and meets every requirement ("consistent", "closed", "manifold",
    "outward", "no_degenerate", "solid", a list of them or a Requirement);
    else false, with the reason in .text."""
    idx, pos, vertex_count, stride, call, _, _ = _mesh(indices, positions, options)
    failure = _CheckFailure()
    ok = _check(_pointer(idx), idx.size, _pointer(pos), vertex_count, stride, _requirements(requirements),
                ctypes.byref(call.options), ctypes.byref(failure))
    call.done(0)
    none = (1 << (8 * ctypes.sizeof(c_size_t))) - 1
    edge = tuple(failure.edge)
    return Check(ok=bool(ok), requirement=Requirement(failure.requirement), count=failure.count,
                 triangle=None if failure.triangle == none else failure.triangle,
                 edge=None if edge == (0xFFFFFFFF, 0xFFFFFFFF) else edge,
                 text=failure.text.decode(),
                 result=_result_name_of(failure.result, str(failure.result)))


def weld(positions, tolerance=0.0, **options):
    """Merge vertices closer than tolerance (meshfix_weld): returns (remap,
    unique_count), remap[v] the lowest-index vertex v welds to (uint32)."""
    pos, vertex_count, stride, position_size = _positions(positions)
    tolerance = _c_value(c_float, tolerance, "tolerance")
    call = _Call((4, position_size), None, **options)  # meshfix_weld reads no normals
    remap = np.empty(vertex_count, np.uint32)
    unique = c_size_t(0)
    result = _weld(_pointer(remap), _pointer(pos), vertex_count, stride, tolerance, ctypes.byref(call.options),
                   ctypes.byref(unique))
    call.done(result)
    return remap, unique.value


def scratch_size(index_count, vertex_count, *, index_dtype=np.uint32, position_dtype=np.float32, **options):
    """Bytes of options.memory.scratch a call with these counts and options
    needs at most (meshfix_scratch_size); pass memory=dict(scratch=buffer)."""
    index_count = _c_value(c_size_t, index_count, "index_count")
    vertex_count = _c_value(c_size_t, vertex_count, "vertex_count")
    call = _Call((np.dtype(index_dtype).itemsize, np.dtype(position_dtype).itemsize), (index_count, vertex_count),
                 **options)
    return _scratch_size(index_count, vertex_count, ctypes.byref(call.options))


PolicyInfo = collections.namedtuple("PolicyInfo", "name description needs_positions needs_normals needs_distance "
                                                  "reads_up casts_rays")
PolicyInfo.__doc__ = "What a policy is and needs (meshfix_policy_info)."


def policy_info(policy):
    """The header's account of a policy (a Policy, its int or its name): its name, a line about it,
    and what it needs (positions, normals, an SDF distance function, the up axis) or does (rays)."""
    pointer = _policy_info(_c_value(c_int, _enum(Policy, policy, "policy"), "policy"))
    if not pointer:
        raise ValueError("meshfix: unknown policy %r (one of %s)" % (policy, ", ".join(m.name.lower() for m in Policy)))
    facts = pointer.contents
    return PolicyInfo(facts.name.decode(), facts.description.decode(), bool(facts.needs_positions),
                      bool(facts.needs_normals), bool(facts.needs_distance), bool(facts.reads_up),
                      bool(facts.casts_rays))


def doubtful_below(policy="auto", **options):
    """The confidence below which a patch's verdict is doubtful, as the report counts it
    (meshfix_doubtful_below): 0.9 under auto, 0.5 under the others, or evidence's min_confidence
    where that is higher."""
    call = _Call((4, 4), None, policy=policy, **options)
    return float(_doubtful_below(ctypes.byref(call.options), int(call.options.policy)))
