// The typed-array API over meshfix.h. A fragment: scripts/build.mjs puts it
// after the constants MESHFIX_LIBRARY_VERSION and MESHFIX_WASM (the
// WebAssembly, base64) and src/layout.js, and before src/gltf.js, in one ES
// module and one CommonJS module; the export list is in build.mjs. The C
// side is src/meshfix_wasm.c: meshfix.h's functions, and the table of the
// structs' fields by which this file reads and writes them.

const POLICIES = ['auto', 'seed', 'majority', 'outward', 'sdf', 'visibility', 'up', 'normals'];
const TOPOLOGIES = ['positions', 'indices', 'weld'];
const VERDICTS = ['clean', 'repaired', 'doubtful', 'not-orientable', 'inconsistent', 'inside-out'];
const REQUIREMENTS = { consistent: 1, closed: 2, manifold: 4, outward: 8, 'no-degenerate': 16, solid: 31 };
const VISIBILITY_FLAGS = { 'coherence-only': 1, 'visibility-only': 2 };
const AXES = { x: [1, 0, 0], y: [0, 1, 0], z: [0, 0, 1], '-x': [-1, 0, 0], '-y': [0, -1, 0], '-z': [0, 0, -1] };
const SUMMARY_BYTES = 512;

// The fields this file handles by name, and as what; the load checks them
// against the table. The others go by the table alone: options as numbers
// their C field holds, the report and the components as they are.
const USES = {
    meshfix_options: {
        index_size: 'integer', position_size: 'integer', topology: 'integer', policy: 'integer', up: 'float[3]',
        'evidence.triangle_normals': 'pointer', 'evidence.triangle_normals_stride': 'integer',
        'evidence.vertex_normals': 'pointer', 'evidence.vertex_normals_stride': 'integer', 'visibility.flags': 'integer',
    },
    meshfix_outputs: {
        flipped: 'pointer', patch_ids: 'pointer', patch_confidence: 'pointer', patch_confidence_capacity: 'integer',
        components: 'pointer', components_capacity: 'integer',
    },
    meshfix_report: { verdict: 'integer', 'mesh.patches': 'integer', 'mesh.components': 'integer' },
    meshfix_component: { closed: 'integer', orientable: 'integer' },
    meshfix_check_failure: {
        result: 'integer', requirement: 'integer', count: 'integer', triangle: 'integer', edge: 'integer[2]', text: 'char[]',
    },
};
// The result codes this file raises itself.
const RESULTS_USED = ['MESHFIX_OK', 'MESHFIX_ERROR_INVALID_ARGUMENT', 'MESHFIX_ERROR_NOT_TRIANGLES', 'MESHFIX_ERROR_OUT_OF_MEMORY'];

const version = MESHFIX_LIBRARY_VERSION;
const supported = typeof WebAssembly === 'object' && typeof WebAssembly.instantiate === 'function';

let wasm = null; // set once `ready` resolves
let loadError = null; // or why it rejected

class MeshfixError extends Error {
    constructor(code, message) {
        super(message);
        this.name = 'MeshfixError';
        this.code = code; // 'MESHFIX_ERROR_INDEX_OUT_OF_RANGE', ...
    }
}

function decodeBase64(text) {
    if (typeof Buffer === 'function')
        return Buffer.from(text, 'base64');
    const binary = atob(text);
    const bytes = new Uint8Array(binary.length);
    for (let i = 0; i < binary.length; ++i)
        bytes[i] = binary.charCodeAt(i);
    return bytes;
}

function readString(e, pointer) {
    const heap = new Uint8Array(e.memory.buffer);
    let end = pointer >>> 0;
    while (heap[end] !== 0)
        ++end;
    return new TextDecoder().decode(heap.subarray(pointer >>> 0, end));
}

function layoutText(e) {
    const size = e.mfjs_layout(0, 0) + 1;
    const pointer = e.mfjs_malloc(size) >>> 0;
    try {
        e.mfjs_layout(pointer, size);
        return readString(e, pointer);
    } finally {
        e.mfjs_free(pointer);
    }
}

// What the WebAssembly says of itself, refused (loudly, before any call)
// when its structs are not what this file reads and writes.
function load(e) {
    const layout = parseLayout(layoutText(e));
    const results = readString(e, e.mfjs_result_codes()).split(',').filter((name) => name !== '');
    const problems = layoutProblems(layout, USES)
        .concat(RESULTS_USED.filter((code) => !results.includes(code)).map((code) => `no result code ${code}`));
    if (problems.length)
        throw new Error(`meshfix-wasm: the WebAssembly's structs are not what this JavaScript reads and writes ` +
                        `(src/meshfix_wasm.c does not list meshfix.h's fields as they are): ${problems.slice(0, 8).join('; ')}`);
    return {
        e,
        layout,
        results,
    };
}

const ready = supported
    ? WebAssembly.instantiate(decodeBase64(MESHFIX_WASM), {
          env: { emscripten_notify_memory_growth() {} }, // views are made anew after every call
      }).then(({ instance }) => {
          const e = instance.exports;
          e._initialize();
          wasm = load(e);
      }).catch((error) => {
          loadError = error;
          throw error;
      })
    : Promise.reject(new Error('meshfix-wasm: WebAssembly is not available here'));
ready.catch(() => {}); // reported to whoever awaits it, never as an unhandled rejection

function instance() {
    if (loadError !== null)
        throw loadError;
    if (wasm === null)
        throw new Error('meshfix-wasm: not ready yet; `await ready` before the first call');
    return wasm;
}

// ---- errors, in the library's words ----

function resultText(status) {
    return readString(wasm.e, wasm.e.meshfix_result_string(status));
}

function libraryError(code, detail) {
    const text = resultText(wasm.results.indexOf(code));
    return new MeshfixError(code, `meshfix: ${text}${detail === undefined ? '' : `: ${detail}`}`);
}

function fail(status) {
    throw new MeshfixError(wasm.results[status] || `MESHFIX_RESULT_${status}`, `meshfix: ${resultText(status)}`);
}

// ---- memory ----

// Runs body(alloc) and frees everything alloc gave out, whatever happens.
function withHeap(body) {
    const { e } = instance();
    const taken = [];
    const alloc = (bytes) => {
        const pointer = e.mfjs_malloc(bytes) >>> 0;
        if (pointer === 0)
            throw libraryError('MESHFIX_ERROR_OUT_OF_MEMORY', 'the WebAssembly heap');
        taken.push(pointer);
        return pointer;
    };
    try {
        return body(alloc, e);
    } finally {
        for (const pointer of taken)
            e.mfjs_free(pointer);
    }
}

function copyIn(e, alloc, array) {
    const pointer = alloc(array.byteLength);
    new Uint8Array(e.memory.buffer, pointer, array.byteLength).set(
        new Uint8Array(array.buffer, array.byteOffset, array.byteLength)
    );
    return pointer;
}

function copyOut(e, Type, pointer, count) {
    return new Type(e.memory.buffer, pointer, count).slice();
}

function memory(e) {
    return new DataView(e.memory.buffer);
}

// A struct, zeroed (the C default), with `values` ({ path: number }) written.
function writeStruct(e, alloc, name, values) {
    const struct = wasm.layout.structs[name];
    const pointer = alloc(struct.size);
    new Uint8Array(e.memory.buffer, pointer, struct.size).fill(0);
    const view = memory(e);
    for (const [path, value] of Object.entries(values || {}))
        setField(view, pointer, struct.byPath.get(path), value);
    return pointer;
}

// A struct as an object: "mesh.triangles_degenerate" as mesh.trianglesDegenerate.
function readStruct(e, name, pointer) {
    const view = memory(e);
    const out = {};
    for (const f of wasm.layout.structs[name].fields) {
        const path = f.name.split('.');
        let node = out;
        for (const key of path.slice(0, -1))
            node = node[key] = node[key] || {};
        node[path[path.length - 1]] = getField(view, pointer, f);
    }
    return out;
}

// ---- options ----

function pick(name, value, list) {
    const i = list.indexOf(value);
    if (i < 0)
        throw new TypeError(`meshfix: ${name} "${value}" is not one of ${list.join(', ')}`);
    return i;
}

function upAxis(up) {
    if (up === undefined || up === null)
        return [0, 0, 0];
    if (typeof up === 'string') {
        if (!(up in AXES))
            throw new TypeError(`meshfix: up "${up}" is not one of ${Object.keys(AXES).join(', ')} or [x, y, z]`);
        return AXES[up];
    }
    if (up.length !== 3)
        throw new TypeError('meshfix: up must be [x, y, z] or an axis name');
    return [up[0], up[1], up[2]];
}

function flagBits(flags, table, what) {
    if (flags === undefined || flags === null)
        return 0;
    if (typeof flags === 'number')
        return flags;
    let bits = 0;
    for (const name of Array.isArray(flags) ? flags : [flags]) {
        if (!(name in table))
            throw new TypeError(`meshfix: ${what} "${name}" is not one of ${Object.keys(table).join(', ')}`);
        bits |= table[name];
    }
    return bits;
}

// Normals as float x y z, `stride` floats apart, `count` of them at least.
function normalData(normals, stride, count, what) {
    if (normals === null || normals === undefined)
        return null;
    const data = normals instanceof Float32Array ? normals : Float32Array.from(normals);
    const step = stride === undefined ? 3 : stride;
    if (!Number.isInteger(step) || step < 3)
        throw new RangeError(`meshfix: ${what}Stride is counted in floats and must be at least 3`);
    if (count > 0 && data.length < (count - 1) * step + 3)
        throw new RangeError(`meshfix: ${what} has ${data.length} floats; ${count} normals need ${(count - 1) * step + 3}`);
    return { data, stride: step };
}

// meshfix_options in the WebAssembly's memory, from the options as given
// (by C path: the table says where each field is).
function writeOptions(e, alloc, options, index, position, triangleCount) {
    const values = { index_size: index.size, position_size: position.size, up: upAxis(options.up) };
    const set = (path, value) => {
        if (value !== undefined && value !== null)
            values[path] = Number(value);
    };
    const evidence = options.evidence || {};
    const visibility = options.visibility || {};
    const policy = options.policy === undefined ? 0 : pick('policy', options.policy, POLICIES);
    if (policy === POLICIES.indexOf('sdf'))
        throw new TypeError('meshfix: policy "sdf" calls a C function for the distance; it is not available from JavaScript');
    set('topology', options.topology === undefined ? 0 : pick('topology', options.topology, TOPOLOGIES));
    set('weld_tolerance', options.weldTolerance);
    set('policy', policy);
    set('seed', options.seed);
    set('evidence.sigma', evidence.sigma);
    set('evidence.min_confidence', evidence.minConfidence);
    const triangleNormals = normalData(evidence.triangleNormals, evidence.triangleNormalsStride, triangleCount, 'triangleNormals');
    if (triangleNormals !== null) {
        set('evidence.triangle_normals', copyIn(e, alloc, triangleNormals.data));
        set('evidence.triangle_normals_stride', triangleNormals.stride * 4);
    }
    const vertexNormals = normalData(evidence.vertexNormals, evidence.vertexNormalsStride, position.count, 'vertexNormals');
    if (vertexNormals !== null) {
        set('evidence.vertex_normals', copyIn(e, alloc, vertexNormals.data));
        set('evidence.vertex_normals_stride', vertexNormals.stride * 4);
    }
    set('visibility.rays', visibility.rays);
    set('visibility.min_samples', visibility.minSamples);
    set('visibility.coherence_distance', visibility.coherenceDistance);
    set('visibility.c0', visibility.c0);
    set('visibility.eps', visibility.eps);
    set('visibility.kv', visibility.kv);
    set('visibility.flags', flagBits(visibility.flags, VISIBILITY_FLAGS, 'visibility flag'));
    return writeStruct(e, alloc, 'meshfix_options', values);
}

// ---- arguments ----

// Indices as the C side takes them (32- or 16-bit), and how to give them back.
function indexData(indices) {
    if (indices instanceof Uint32Array)
        return { data: indices, size: 4, Type: Uint32Array };
    if (indices instanceof Uint16Array)
        return { data: indices, size: 2, Type: Uint16Array };
    if (indices instanceof Uint8Array)
        return { data: Uint16Array.from(indices), size: 2, Type: Uint8Array };
    if (Array.isArray(indices) || ArrayBuffer.isView(indices)) {
        for (const i of indices)
            if (!Number.isInteger(i) || i < 0 || i > 0xffffffff)
                throw new RangeError(`meshfix: index ${i} is not an unsigned 32-bit integer`);
        return { data: Uint32Array.from(indices), size: 4, Type: Uint32Array };
    }
    throw new TypeError('meshfix: indices must be a Uint32Array, Uint16Array, Uint8Array or an array of integers');
}

// Positions (or null), their element stride and the vertex count.
function positionData(positions, indices, options) {
    const stride = options.positionsStride === undefined ? 3 : options.positionsStride;
    if (!Number.isInteger(stride) || stride < 3)
        throw new RangeError('meshfix: positionsStride is counted in elements (floats) and must be at least 3');
    if (positions === null || positions === undefined) {
        let count = options.vertexCount;
        if (count === undefined) {
            count = 0;
            for (let i = 0; i < indices.length; ++i)
                if (indices[i] >= count)
                    count = indices[i] + 1;
        }
        return { data: null, size: 4, stride, count };
    }
    let data = positions;
    if (!(positions instanceof Float32Array) && !(positions instanceof Float64Array)) {
        if (!Array.isArray(positions) && !ArrayBuffer.isView(positions))
            throw new TypeError('meshfix: positions must be a Float32Array, a Float64Array, an array of numbers or null');
        data = Float64Array.from(positions); // JavaScript numbers are doubles: nothing rounded
    }
    const available = data.length >= 3 ? Math.floor((data.length - 3) / stride) + 1 : 0;
    const count = options.vertexCount === undefined ? available : options.vertexCount;
    if (!Number.isInteger(count) || count < 0 || count > available)
        throw new RangeError(`meshfix: vertexCount ${count} needs more positions than the ${data.length} given`);
    return { data, size: data.BYTES_PER_ELEMENT, stride, count };
}

function requirementBits(requirements) {
    return flagBits(requirements, REQUIREMENTS, 'requirement');
}

function readReport(e, pointer) {
    const report = readStruct(e, 'meshfix_report', pointer);
    report.verdict = VERDICTS[report.verdict] || String(report.verdict);
    return report;
}

function readComponents(e, pointer, count) {
    const size = wasm.layout.structs.meshfix_component.size;
    const components = [];
    for (let i = 0; i < count; ++i) {
        const c = readStruct(e, 'meshfix_component', pointer + i * size);
        c.closed = c.closed !== 0;
        c.orientable = c.orientable !== 0;
        components.push(c);
    }
    return components;
}

// ---- calls ----

// orient and inspect: one run of the library, its outputs copied out.
function run(inspectOnly, indices, positions, options) {
    options = options || {};
    const index = indexData(indices);
    if (index.data.length % 3 !== 0)
        throw libraryError('MESHFIX_ERROR_NOT_TRIANGLES');
    const position = positionData(positions, index.data, options);
    const triangles = index.data.length / 3;
    return withHeap((alloc, e) => {
        const indexPointer = copyIn(e, alloc, index.data);
        const positionPointer = position.data === null ? 0 : copyIn(e, alloc, position.data);
        const optionPointer = writeOptions(e, alloc, options, index, position, triangles);
        const reportPointer = writeStruct(e, alloc, 'meshfix_report');
        const summaryPointer = alloc(SUMMARY_BYTES);
        const flippedPointer = inspectOnly ? 0 : alloc(triangles);
        const patchPointer = alloc(4 * triangles);
        const confidencePointer = inspectOnly ? 0 : alloc(4 * triangles);
        const componentCapacity = options.components ? triangles : 0;
        const componentPointer = componentCapacity ? alloc(wasm.layout.structs.meshfix_component.size * componentCapacity) : 0;
        const outputs = writeStruct(e, alloc, 'meshfix_outputs', {
            flipped: flippedPointer, patch_ids: patchPointer, patch_confidence: confidencePointer,
            patch_confidence_capacity: inspectOnly ? 0 : triangles, components: componentPointer,
            components_capacity: componentCapacity,
        });
        const stride = position.stride * position.size;
        const status = inspectOnly
            ? e.meshfix_inspect(indexPointer, index.data.length, positionPointer, position.count, stride, optionPointer,
                                reportPointer, outputs)
            : e.meshfix_orient(indexPointer, indexPointer, index.data.length, positionPointer, position.count, stride,
                               optionPointer, reportPointer, outputs);
        if (status !== 0)
            fail(status);
        e.meshfix_summary(reportPointer, summaryPointer, SUMMARY_BYTES);
        const report = readReport(e, reportPointer);
        const result = {
            report,
            summary: readString(e, summaryPointer),
            patchIds: copyOut(e, Uint32Array, patchPointer, triangles),
        };
        if (!inspectOnly) {
            const fixed = copyOut(e, index.size === 4 ? Uint32Array : Uint16Array, indexPointer, index.data.length);
            let target;
            if (options.inPlace && index.Type === indices.constructor) {
                indices.set(fixed);
                target = indices;
            } else {
                target = index.Type === fixed.constructor ? fixed : index.Type.from(fixed);
            }
            result.indices = target;
            result.flipped = copyOut(e, Uint8Array, flippedPointer, triangles);
            result.patchConfidence = copyOut(e, Float32Array, confidencePointer, Math.min(report.mesh.patches, triangles));
        }
        if (componentCapacity)
            result.components = readComponents(e, componentPointer, Math.min(report.mesh.components, componentCapacity));
        return result;
    });
}

function orient(indices, positions, options) {
    const result = run(false, indices, positions, options);
    return {
        indices: result.indices,
        flipped: result.flipped,
        report: result.report,
        summary: result.summary,
        patchIds: result.patchIds,
        patchConfidence: result.patchConfidence,
        ...(result.components ? { components: result.components } : {}),
    };
}

function inspect(indices, positions, options) {
    return run(true, indices, positions, options);
}

function check(indices, positions, requirements, options) {
    options = options || {};
    const index = indexData(indices);
    const position = positionData(positions, index.data, options);
    const bits = requirementBits(requirements);
    return withHeap((alloc, e) => {
        const indexPointer = copyIn(e, alloc, index.data);
        const positionPointer = position.data === null ? 0 : copyIn(e, alloc, position.data);
        const optionPointer = writeOptions(e, alloc, options, index, position, Math.floor(index.data.length / 3));
        const failurePointer = writeStruct(e, alloc, 'meshfix_check_failure');
        const ok = e.meshfix_check(indexPointer, index.data.length, positionPointer, position.count,
                                   position.stride * position.size, bits, optionPointer, failurePointer) !== 0;
        const f = readStruct(e, 'meshfix_check_failure', failurePointer);
        const none = (path) => fieldRange(wasm.layout.structs.meshfix_check_failure.byPath.get(path)).most; // (size_t)-1, 0xFFFFFFFF
        const requirement = Object.keys(REQUIREMENTS).find((name) => REQUIREMENTS[name] === f.requirement);
        return {
            ok,
            text: f.text,
            result: wasm.results[f.result] || `MESHFIX_RESULT_${f.result}`,
            requirement: f.requirement === 0 ? null : requirement || f.requirement,
            count: f.count,
            triangle: f.triangle === none('triangle') ? null : f.triangle,
            edge: f.edge[0] === none('edge') ? null : f.edge,
        };
    });
}

function weld(positions, tolerance, options) {
    options = options || {};
    const position = positionData(positions, [], options);
    if (position.data === null)
        throw new TypeError('meshfix: weld needs positions');
    return withHeap((alloc, e) => {
        const positionPointer = copyIn(e, alloc, position.data);
        const optionPointer = writeStruct(e, alloc, 'meshfix_options', { position_size: position.size });
        const remapPointer = alloc(4 * position.count);
        const size = wasm.layout.types.size_t;
        const uniquePointer = alloc(size.size);
        const status = e.meshfix_weld(remapPointer, positionPointer, position.count, position.stride * position.size,
                                      tolerance || 0, optionPointer, uniquePointer);
        if (status !== 0)
            fail(status);
        return {
            remap: copyOut(e, Uint32Array, remapPointer, position.count),
            uniqueCount: getField(memory(e), uniquePointer, size),
        };
    });
}
