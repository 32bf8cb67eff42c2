// The typed-array API over meshfix.h. A fragment: scripts/build.mjs puts it
// after the constants MESHFIX_LIBRARY_VERSION and MESHFIX_WASM (the
// WebAssembly, base64) and src/layout.js, and before src/gltf.js, in one ES
// module and one CommonJS module; the export list is in build.mjs. The C
// side is src/meshfix_wasm.c: meshfix.h's functions, and the table of the
// structs' fields by which this file reads and writes them.

const TOPOLOGIES = ['positions', 'indices', 'weld'];
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
        components: 'pointer', components_capacity: 'integer', patch_evidence: 'pointer',
        patch_evidence_capacity: 'integer',
    },
    meshfix_report: { verdict: 'integer', verdict_before: 'integer', 'mesh.patches': 'integer', 'mesh.components': 'integer' },
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
        policies: Array.from({ length: e.mfjs_policy_count() }, (_, i) => readString(e, e.meshfix_policy_string(i))),
        callsC: Array.from({ length: e.mfjs_policy_count() }, (_, i) => e.mfjs_policy_needs_distance(i) !== 0),
        // meshfix_verdict_string's words, hyphenated: 'not-orientable'
        verdicts: Array.from({ length: e.mfjs_verdict_count() },
                             (_, i) => readString(e, e.meshfix_verdict_string(i)).replace(/ /g, '-')),
        options: new Map(layout.structs.meshfix_options.fields.map((f) => [f.name, f])),
        schemas: { call: optionSchema(layout, CALL_OPTIONS), weld: optionSchema(null, WELD_OPTIONS) },
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

// An option refused before the call: the library's MESHFIX_ERROR_INVALID_ARGUMENT, naming it.
function optionError(path, problem) {
    return libraryError('MESHFIX_ERROR_INVALID_ARGUMENT', `${path} ${problem}`);
}

function show(value) {
    if (typeof value === 'string')
        return JSON.stringify(value);
    if (value === null || typeof value !== 'object' && typeof value !== 'function')
        return String(value);
    return Array.isArray(value) ? 'an array' : typeof value === 'function' ? 'a function' : `a ${value.constructor ? value.constructor.name : 'object'}`;
}

function own(table, key) {
    return Object.prototype.hasOwnProperty.call(table, key);
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

// How an option is taken, for those not a plain number of its C field:
// take(value, path, field) returns the value for C (undefined: none).
const OPTION_TAKERS = {
    policy: takePolicy,
    topology: (value, path) => takeName(value, path, TOPOLOGIES),
    up: takeUp,
    'evidence.triangleNormals': takeNormals,
    'evidence.triangleNormalsStride': takeFloatStride,
    'evidence.vertexNormals': takeNormals,
    'evidence.vertexNormalsStride': takeFloatStride,
    'visibility.flags': takeFlags,
};
// meshfix_options fields JavaScript does not offer: set from the arrays, or C callbacks and memory.
const OPTIONS_INTERNAL = ['indexSize', 'positionSize', 'sdf', 'memory', 'parallelFor', 'parallelUser'];
// JavaScript's own options, of orient, inspect and check, and of weld.
const CALL_OPTIONS = { positionsStride: takeSize, vertexCount: takeSize, components: takeBoolean, inPlace: takeBoolean };
const WELD_OPTIONS = { positionsStride: takeSize, vertexCount: takeSize };

function takeNumber(value, path, field) {
    if (!fieldHolds(field, value))
        throw optionError(path, `${show(value)} is not ${fieldType(field)}, what its C field holds`);
    return value;
}

function takeSize(value, path) {
    return takeNumber(value, path, instance().layout.types.size_t);
}

function takeBoolean(value, path) {
    if (typeof value !== 'boolean')
        throw optionError(path, `${show(value)} is not true or false`);
    return value;
}

function takeFunction(value, path) {
    if (typeof value !== 'function')
        throw optionError(path, `${show(value)} is not a function`);
    return value;
}

function takeName(value, path, names) {
    const i = typeof value === 'string' ? names.indexOf(value) : -1;
    if (i < 0)
        throw optionError(path, `${show(value)} is not one of ${names.join(', ')}`);
    return i;
}

// The names the library knows (meshfix_policy_string), less those that call a C function for the
// distance (meshfix_policy_info's needs_distance: "sdf").
function policyNames() {
    const { policies, callsC } = instance();
    return policies.filter((_, i) => !callsC[i]);
}

function takePolicy(value, path) {
    const policy = typeof value === 'string' && !value.includes('\0') ? policyFromString(value) : wasm.policies.length;
    if (policy < wasm.policies.length && wasm.callsC[policy])
        throw optionError(path, `"${value}" calls a C function for the distance; it is not available from JavaScript`);
    if (policy >= wasm.policies.length)
        throw optionError(path, `${show(value)} is not one of ${policyNames().join(', ')}`);
    return policy;
}

function policyFromString(name) {
    return withHeap((alloc, e) => {
        const bytes = new TextEncoder().encode(`${name}\0`);
        return e.meshfix_policy_from_string(copyIn(e, alloc, bytes));
    });
}

function takeUp(value, path, field) {
    if (typeof value === 'string') {
        if (!own(AXES, value))
            throw optionError(path, `${show(value)} is not one of ${Object.keys(AXES).join(', ')} or [x, y, z]`);
        return AXES[value];
    }
    if (!Array.isArray(value) && !ArrayBuffer.isView(value) || value.length !== field.count)
        throw optionError(path, `${show(value)} is not an axis name or [x, y, z]`);
    return Array.from(value, (v, i) => takeNumber(v, `${path}[${i}]`, field));
}

function takeFlags(value, path, field) {
    if (typeof value === 'number')
        return takeNumber(value, path, field);
    let bits = 0;
    for (const name of Array.isArray(value) ? value : [value]) {
        if (typeof name !== 'string' || !own(VISIBILITY_FLAGS, name))
            throw optionError(path, `${show(name)} is not one of ${Object.keys(VISIBILITY_FLAGS).join(', ')} or a number`);
        bits |= VISIBILITY_FLAGS[name];
    }
    return bits;
}

// Normals as float x y z (null: none); copied in once the count is known (writeOptions).
function takeNormals(value, path) {
    if (value === null)
        return undefined;
    if (value instanceof Float32Array)
        return value;
    if (!Array.isArray(value) && !ArrayBuffer.isView(value))
        throw optionError(path, `${show(value)} is not a Float32Array or an array of numbers`);
    return Float32Array.from(value);
}

// A stride counted in floats, into the bytes of its C field (0, as in C: 3 floats).
function takeFloatStride(value, path, field) {
    if (!Number.isInteger(value) || value < 0 || !fieldHolds(field, 4 * value))
        throw optionError(path, `${show(value)} is not a count of floats whose bytes its C field holds ` +
                                `(0 to ${Math.floor(fieldRange(field).most / 4)})`);
    return 4 * value;
}

// The options a function takes, by path ('visibility.rays'), each with its
// take and C field: with a layout, meshfix_options' fields by their
// camelCase names, less the internal ones and `omit`; and `own`, taken by
// JavaScript.
function optionSchema(layout, own, omit) {
    const schema = new Map();
    const left = [...OPTIONS_INTERNAL, ...(omit || [])];
    for (const field of layout === null ? [] : layout.structs.meshfix_options.fields) {
        if (left.some((p) => field.name === p || field.name.startsWith(`${p}.`)))
            continue;
        const take = OPTION_TAKERS[field.name] || (field.kind !== 'p' && field.count === 1 ? takeNumber : null);
        if (take !== null)
            schema.set(field.name, { take, field });
    }
    for (const [path, take] of Object.entries(own))
        schema.set(path, { take, field: null });
    return schema;
}

// The names a schema has at one level: 'policy', ..., 'evidence', 'visibility'.
function optionNames(schema, prefix) {
    const names = new Set();
    for (const path of schema.keys())
        if (prefix === '' || path.startsWith(`${prefix}.`))
            names.add(path.slice(prefix === '' ? 0 : prefix.length + 1).split('.')[0]);
    return [...names];
}

// The options given, checked against a schema: a Map from path to the value
// for C (or for this file). A name the schema does not have is refused, and
// so is a value its C field cannot hold; undefined is as if not given.
function takeOptions(options, schema, prefix = '', taken = new Map()) {
    if (options === undefined || options === null && prefix === '')
        return taken;
    if (typeof options !== 'object' || options === null || Array.isArray(options))
        throw optionError(prefix || 'options', `${show(options)} is not an object of options`);
    for (const [key, value] of Object.entries(options)) {
        const path = prefix === '' ? key : `${prefix}.${key}`;
        const entry = key.includes('.') ? undefined : schema.get(path); // 'evidence.sigma' is no name of its own
        if (value === undefined)
            continue;
        if (entry !== undefined) {
            const v = entry.take(value, path, entry.field);
            if (v !== undefined)
                taken.set(path, v);
        } else if (!key.includes('.') && optionNames(schema, path).length > 0) {
            takeOptions(value, schema, path, taken);
        } else {
            throw optionError(path, `is not an option${prefix === '' ? '' : ` of ${prefix}`} (${optionNames(schema, prefix).join(', ')})`);
        }
    }
    return taken;
}

// meshfix_options in the WebAssembly's memory, from the options taken;
// normals copied in beside them, checked against the count they cover.
function writeOptions(e, alloc, taken, index, position, triangleCount) {
    const values = { index_size: index.size, position_size: position.size };
    for (const [path, value] of taken) {
        const field = wasm.options.get(path);
        if (field !== undefined && field.kind !== 'p')
            values[field.path] = value;
    }
    for (const [path, count] of [['evidence.triangleNormals', triangleCount], ['evidence.vertexNormals', position.count]]) {
        const normals = taken.get(path);
        if (normals === undefined)
            continue;
        const step = (taken.get(`${path}Stride`) || 12) / 4;
        if (count > 0 && normals.length < (count - 1) * step + 3)
            throw optionError(path, `has ${normals.length} floats; ${count} normals, ${step} floats apart, need ${(count - 1) * step + 3}`);
        values[wasm.options.get(path).path] = copyIn(e, alloc, normals);
    }
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

// Positions (or null), their element stride as given (0: 3, as in C) and the vertex count.
function positionData(positions, indices, taken) {
    const stride = taken.has('positionsStride') ? taken.get('positionsStride') : 3;
    let count = taken.get('vertexCount');
    if (positions === null || positions === undefined) {
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
    if (!fieldHolds(wasm.layout.types.size_t, stride * data.BYTES_PER_ELEMENT))
        throw optionError('positionsStride', `${stride} is more bytes than the C stride holds`);
    const step = stride || 3;
    const available = data.length >= 3 ? Math.floor((data.length - 3) / step) + 1 : 0;
    if (count === undefined)
        count = available;
    else if (count > available)
        throw optionError('vertexCount', `${count} needs more positions than the ${data.length} given`);
    return { data, size: data.BYTES_PER_ELEMENT, stride, count };
}

function requirementBits(requirements) {
    if (requirements === undefined || requirements === null)
        return 0;
    if (typeof requirements === 'number') {
        if (!Number.isInteger(requirements) || requirements < 0 || requirements > 0xffffffff)
            throw new RangeError(`meshfix: requirements ${requirements} is not an unsigned 32-bit integer`);
        return requirements;
    }
    let bits = 0;
    for (const name of Array.isArray(requirements) ? requirements : [requirements]) {
        if (typeof name !== 'string' || !own(REQUIREMENTS, name))
            throw new TypeError(`meshfix: requirement ${show(name)} is not one of ${Object.keys(REQUIREMENTS).join(', ')}`);
        bits |= REQUIREMENTS[name];
    }
    return bits;
}

function readReport(e, pointer) {
    const report = readStruct(e, 'meshfix_report', pointer);
    report.verdict = wasm.verdicts[report.verdict] || String(report.verdict);
    report.verdictBefore = wasm.verdicts[report.verdictBefore] || String(report.verdictBefore);
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
    const taken = takeOptions(options, instance().schemas.call);
    const index = indexData(indices);
    if (index.data.length % 3 !== 0)
        throw libraryError('MESHFIX_ERROR_NOT_TRIANGLES');
    const position = positionData(positions, index.data, taken);
    const triangles = index.data.length / 3;
    return withHeap((alloc, e) => {
        const indexPointer = copyIn(e, alloc, index.data);
        const positionPointer = position.data === null ? 0 : copyIn(e, alloc, position.data);
        const optionPointer = writeOptions(e, alloc, taken, index, position, triangles);
        const reportPointer = writeStruct(e, alloc, 'meshfix_report');
        const summaryPointer = alloc(SUMMARY_BYTES);
        const flippedPointer = inspectOnly ? 0 : alloc(triangles);
        const patchPointer = alloc(4 * triangles);
        const confidencePointer = inspectOnly ? 0 : alloc(4 * triangles);
        const evidencePointer = inspectOnly ? 0 : alloc(triangles);
        const componentCapacity = taken.get('components') ? triangles : 0;
        const componentPointer = componentCapacity ? alloc(wasm.layout.structs.meshfix_component.size * componentCapacity) : 0;
        const outputs = writeStruct(e, alloc, 'meshfix_outputs', {
            flipped: flippedPointer, patch_ids: patchPointer, patch_confidence: confidencePointer,
            patch_confidence_capacity: inspectOnly ? 0 : triangles, components: componentPointer,
            components_capacity: componentCapacity, patch_evidence: evidencePointer,
            patch_evidence_capacity: inspectOnly ? 0 : triangles,
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
            if (taken.get('inPlace') && index.Type === indices.constructor) {
                indices.set(fixed);
                target = indices;
            } else {
                target = index.Type === fixed.constructor ? fixed : index.Type.from(fixed);
            }
            result.indices = target;
            result.flipped = copyOut(e, Uint8Array, flippedPointer, triangles);
            result.patchConfidence = copyOut(e, Float32Array, confidencePointer, Math.min(report.mesh.patches, triangles));
            result.patchEvidence = copyOut(e, Uint8Array, evidencePointer, Math.min(report.mesh.patches, triangles));
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
        patchEvidence: result.patchEvidence,
        ...(result.components ? { components: result.components } : {}),
    };
}

function inspect(indices, positions, options) {
    return run(true, indices, positions, options);
}

function check(indices, positions, requirements, options) {
    const taken = takeOptions(options, instance().schemas.call);
    const index = indexData(indices);
    const position = positionData(positions, index.data, taken);
    const bits = requirementBits(requirements);
    return withHeap((alloc, e) => {
        const indexPointer = copyIn(e, alloc, index.data);
        const positionPointer = position.data === null ? 0 : copyIn(e, alloc, position.data);
        const optionPointer = writeOptions(e, alloc, taken, index, position, Math.floor(index.data.length / 3));
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
    const taken = takeOptions(options, instance().schemas.weld);
    if (tolerance !== undefined && !fieldHolds({ kind: 'f', element: 4 }, tolerance))
        throw optionError('tolerance', `${show(tolerance)} is not a finite 32-bit float, what the C argument holds`);
    const position = positionData(positions, [], taken);
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
