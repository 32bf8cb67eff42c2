// meshfix-wasm: meshfix.h (triangle winding repair) compiled to WebAssembly.
// Types for dist/meshfix.mjs and dist/meshfix.cjs. MIT license.

/** Resolves once the WebAssembly is compiled; every call below needs it. */
export const ready: Promise<void>;
/** False where WebAssembly is not available (then `ready` rejects). */
export const supported: boolean;
/** The version of meshfix.h inside, "0.2.0". */
export const version: string;

/** Which way each consistently wound patch ends up facing (meshfix_policy). `sdf` is C only. */
export type Policy = 'auto' | 'seed' | 'majority' | 'outward' | 'visibility' | 'up' | 'normals';
/** Which corners are one vertex for the edge map (meshfix_topology). */
export type Topology = 'positions' | 'indices' | 'weld';
export type Axis = 'x' | 'y' | 'z' | '-x' | '-y' | '-z';
export type Verdict = 'clean' | 'repaired' | 'doubtful' | 'not-orientable' | 'inconsistent' | 'inside-out';
export type Requirement = 'consistent' | 'closed' | 'manifold' | 'outward' | 'no-degenerate' | 'solid';
export type VisibilityFlag = 'coherence-only' | 'visibility-only';

export type Indices = Uint32Array | Uint16Array | Uint8Array | ArrayLike<number>;
export type Positions = Float32Array | Float64Array | ArrayLike<number>;

/**
 * meshfix_options; every field optional, as zero is the default in C. A property set to
 * `undefined` counts as left out (so do `null` options and `null` normals). Anything else is
 * checked, never changed to the default: an unknown name at any level, a value of the wrong
 * type, or a number its C field cannot hold (negative or fractional for an unsigned field,
 * above 2^32 - 1 for unsigned int and wasm32's size_t, NaN, Infinity) throws a MeshfixError
 * with code 'MESHFIX_ERROR_INVALID_ARGUMENT', the library's text and the option's name. What the
 * C field holds but the library refuses (rays above 2^24, ...) throws the same from the library.
 * Not offered: sdf and memory (C callbacks and memory), parallel_for.
 */
export interface Options {
    /** Floats (or doubles) from one vertex's x to the next one's; default 3 (0 means 3, as in C). */
    positionsStride?: number;
    /** Default: all the positions given (or, without positions, the highest index + 1). */
    vertexCount?: number;
    topology?: Topology;
    weldTolerance?: number;
    /** 'normals' needs positions and evidence normals (else MESHFIX_ERROR_POSITIONS_REQUIRED, MESHFIX_ERROR_NORMALS_REQUIRED). */
    policy?: Policy;
    /** The axis of policy 'up'; default +z ('y' in the glTF transform). */
    up?: Axis | [number, number, number];
    /** Seed of the ray streams; 0 = a fixed default. */
    seed?: number;
    evidence?: {
        /** A ray vote counts beyond this many standard errors (default 3). */
        sigma?: number;
        /** Below this confidence a patch keeps the side most of its area faces (default 0). */
        minConfidence?: number;
        /** Normals you have (STL facets, OBJ vn, glTF NORMAL): evidence under 'auto', the rule under 'normals'. */
        triangleNormals?: Float32Array | ArrayLike<number> | null;
        /** In floats; default 3 (0 means 3). */
        triangleNormalsStride?: number;
        vertexNormals?: Float32Array | ArrayLike<number> | null;
        vertexNormalsStride?: number;
    };
    visibility?: {
        rays?: number;
        minSamples?: number;
        coherenceDistance?: number;
        c0?: number;
        eps?: number;
        kv?: number;
        flags?: number | VisibilityFlag | VisibilityFlag[];
    };
    /** Also return per-component facts (96 bytes of WebAssembly memory per triangle meanwhile). */
    components?: boolean;
    /** orient: write the repaired indices into the array given (a Uint32Array, Uint16Array or Uint8Array). */
    inPlace?: boolean;
}

/** meshfix_mesh_facts: what the mesh is (orient: as returned; inspect: as given). */
export interface MeshFacts {
    triangles: number;
    trianglesDegenerate: number;
    trianglesZeroArea: number;
    trianglesDuplicate: number;
    verticesUsed: number;
    verticesJoined: number;
    verticesNonFinite: number;
    verticesNonManifold: number;
    edges: number;
    edgesBoundary: number;
    edgesManifold: number;
    edgesNonManifold: number;
    edgesInconsistent: number;
    patches: number;
    patchesClosed: number;
    patchesInsideOut: number;
    components: number;
    componentsClosed: number;
    componentsNonOrientable: number;
    eulerCharacteristic: number;
    area: number;
    signedVolume: number;
}

/** meshfix_evidence_counts: what decided the patches. */
export interface EvidenceCounts {
    patchesByVolume: number;
    patchesByParity: number;
    patchesByVisibility: number;
    patchesByNormals: number;
    patchesKept: number;
    shellsInward: number;
    raysCast: number;
    patchPairs: number;
    patchesMerged: number;
    pairsConflicting: number;
    sdfEvaluations: number;
    trianglesSdfDisagree: number;
    /** flipped although their clear normal agreed with their winding as given */
    trianglesAgainstNormals: number;
}

/** meshfix_report. */
export interface Report {
    verdict: Verdict;
    trianglesFlipped: number;
    patchesFlipped: number;
    patchesDoubtful: number;
    trianglesDoubtful: number;
    areaDoubtful: number;
    /** the mesh as given: what inspect reports of it */
    edgesInconsistentBefore: number;
    verdictBefore: Verdict;
    patchesInsideOutBefore: number;
    signedVolumeBefore: number;
    mesh: MeshFacts;
    evidence: EvidenceCounts;
}

/** meshfix_component. */
export interface Component {
    firstTriangle: number;
    triangles: number;
    vertices: number;
    edges: number;
    edgesBoundary: number;
    edgesNonManifold: number;
    patches: number;
    eulerCharacteristic: number;
    closed: boolean;
    orientable: boolean;
    area: number;
    signedVolume: number;
}

export interface OrientResult<I> {
    /** The repaired indices: a new array of the input's type (the input itself with inPlace). */
    indices: I;
    /** Per triangle, 1 when flipped. */
    flipped: Uint8Array;
    report: Report;
    /** meshfix_summary: "fixed 72 triangles in 3 patches", "clean: nothing to flip (12 triangles, 1 patch)". */
    summary: string;
    /** Per triangle; 0xFFFFFFFF for a degenerate one. */
    patchIds: Uint32Array;
    /** Per patch, the margin of its verdict, 0 to 1. */
    patchConfidence: Float32Array;
    /** Per patch, what decided it (meshfix_evidence): 0 nothing (kept), 1 volume, 2 parity, 3 visibility, 4 normals, 5 the policy's rule. */
    patchEvidence: Uint8Array;
    components?: Component[];
}

export interface InspectResult {
    report: Report;
    summary: string;
    patchIds: Uint32Array;
    components?: Component[];
}

export interface CheckResult {
    ok: boolean;
    /** "ok", or the reason: "not consistent: 3 edges run the same way in two or more triangles; edge 1-2 ..." */
    text: string;
    /** 'MESHFIX_OK', or why the mesh is not valid input ('MESHFIX_ERROR_INDEX_OUT_OF_RANGE', ...). */
    result: string;
    /** The first requirement that does not hold, or null. */
    requirement: Requirement | null;
    count: number;
    triangle: number | null;
    edge: [number, number] | null;
}

/**
 * Thrown when the library refuses a mesh or an option; `code` is the C name, e.g.
 * 'MESHFIX_ERROR_INDEX_OUT_OF_RANGE', the message the library's text (meshfix_result_string).
 */
export class MeshfixError extends Error {
    code: string;
}

type SameIndices<I> = I extends Uint32Array | Uint16Array | Uint8Array ? I : Uint32Array;

/** meshfix_orient: repairs winding; triangles keep their order, a flipped (a, b, c) becomes (a, c, b). */
export function orient<I extends Indices>(indices: I, positions?: Positions | null, options?: Options): OrientResult<SameIndices<I>>;
/** meshfix_inspect: reports, never changes. */
export function inspect(indices: Indices, positions?: Positions | null, options?: Options): InspectResult;
/** meshfix_check: ok, or the first requirement that fails and why (default 'consistent'). */
export function check(indices: Indices, positions?: Positions | null, requirements?: Requirement | Requirement[] | number,
                      options?: Options): CheckResult;
/** meshfix_weld: remap[v] is the lowest vertex v welds to within tolerance (0: equal positions); options: only these two. */
export function weld(positions: Positions, tolerance?: number, options?: Pick<Options, 'positionsStride' | 'vertexCount'>):
    { remap: Uint32Array; uniqueCount: number };

// ---- glTF-Transform ----

/** What the transform did, mesh by mesh and primitive by primitive. */
export interface GltfReport {
    dryRun: boolean;
    triangles: number;
    trianglesFlipped: number;
    meshesChanged: number;
    primitivesChanged: number;
    accessorsCloned: number;
    accessorsCreated: number;
    accessorsRemoved: number;
    primitivesConverted: number;
    meshes: Array<{
        index: number;
        name: string;
        /** triangle primitives taken into the decision */
        primitives: number;
        triangles: number;
        trianglesFlipped: number;
        verdict?: Verdict;
        summary?: string;
        report?: Report;
        /** set when the library refused the mesh; it is left as it was */
        error?: string;
    }>;
    primitives: Array<{
        mesh: number;
        primitive: number;
        mode: 'TRIANGLES' | 'TRIANGLE_STRIP' | 'TRIANGLE_FAN';
        /** index bits (8, 16, 32), or null when not indexed */
        indices: 8 | 16 | 32 | null;
        triangles: number;
        trianglesFlipped: number;
        action: string;
    }>;
    skipped: Array<{ mesh: number; primitive: number; reason: string }>;
    /** nodes whose world transform has a negative determinant (renderers reverse their winding): never changed */
    mirroredNodes: Array<{ index: number; name: string; mesh: number; determinant: number }>;
    /** double-sided materials on the triangle primitives (they hide bad winding): never changed */
    doubleSidedMaterials: Array<{ index: number; name: string; primitives: number; primitivesFlipped: number }>;
    /** compression extensions in use (decoded by the I/O before the transform, when registered) */
    compression: string[];
    summary: string;
}

export interface GltfMeshInput {
    mesh: unknown;
    meshIndex: number;
    /** the mesh's triangles in mesh space, over `positions` */
    indices: Uint32Array;
    positions: Float32Array;
    vertexNormals: Float32Array | null;
    options: Options;
    result: OrientResult<Uint32Array>;
    primitives: Array<{ primitive: unknown; index: number; mode: number; firstTriangle: number; triangleCount: number }>;
}

/**
 * orient's options but one call's own (the normals are each mesh's NORMAL), and the transform's;
 * checked as orient's before any mesh: a bad one rejects the transform's promise.
 */
export interface GltfOptions extends Omit<Options, 'positionsStride' | 'vertexCount' | 'inPlace' | 'components' | 'evidence'> {
    evidence?: Omit<NonNullable<Options['evidence']>, 'triangleNormals' | 'triangleNormalsStride' | 'vertexNormals' | 'vertexNormalsStride'>;
    /** Pass each primitive's NORMAL as evidence (default true). */
    normals?: boolean;
    /** Report what would change, write nothing. */
    dryRun?: boolean;
    onReport?: (report: GltfReport) => void;
    /** Called per mesh with the arrays the library saw and its result (for inspection and tests). */
    onMesh?: (input: GltfMeshInput) => void;
}

/** The part of glTF-Transform's Document the transform uses (so these types need no @gltf-transform/core). */
export interface GltfDocument {
    getRoot(): any;
    getLogger(): any;
    createAccessor(name?: string): any;
    createBuffer(name?: string): any;
}

/** A glTF-Transform transform: `await document.transform(meshfix())`. */
export function meshfix(options?: GltfOptions): (document: GltfDocument) => Promise<void>;
