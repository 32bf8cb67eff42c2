// The typed-array API over meshfix.h. A fragment: scripts/build.mjs puts it
// after the constants MESHFIX_LIBRARY_VERSION and MESHFIX_WASM (the
// WebAssembly, base64) and before src/gltf.js, in one ES module and one
// CommonJS module; the export list is in build.mjs. The C side is
// src/meshfix_wasm.c: options, report and components cross as arrays of
// doubles whose field names it lists.

const POLICIES = ['auto', 'seed', 'majority', 'outward', 'sdf', 'visibility', 'up', 'normals'];
const TOPOLOGIES = ['positions', 'indices', 'weld'];
const VERDICTS = ['clean', 'repaired', 'doubtful', 'not-orientable', 'inconsistent', 'inside-out'];
const REQUIREMENTS = { consistent: 1, closed: 2, manifold: 4, outward: 8, 'no-degenerate': 16, solid: 31 };
const VISIBILITY_FLAGS = { 'coherence-only': 1, 'visibility-only': 2 };
const AXES = { x: [1, 0, 0], y: [0, 1, 0], z: [0, 0, 1], '-x': [-1, 0, 0], '-y': [0, -1, 0], '-z': [0, 0, -1] };
const SUMMARY_BYTES = 512;
const CHECK_TEXT_BYTES = 200;

const version = MESHFIX_LIBRARY_VERSION;
const supported = typeof WebAssembly === 'object' && typeof WebAssembly.instantiate === 'function';

let wasm = null; // set once `ready` resolves

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

function fieldIndex(list) {
    const names = list.split(',').filter((name) => name !== '');
    const index = new Map(names.map((name, i) => [name, i]));
    return { names, index };
}

const ready = supported
    ? WebAssembly.instantiate(decodeBase64(MESHFIX_WASM), {
          env: { emscripten_notify_memory_growth() {} }, // views are made anew after every call
      }).then(({ instance }) => {
          const e = instance.exports;
          e._initialize();
          wasm = {
              e,
              options: fieldIndex(readString(e, e.mfjs_option_fields())),
              report: fieldIndex(readString(e, e.mfjs_report_fields())),
              component: fieldIndex(readString(e, e.mfjs_component_fields())),
              results: fieldIndex(readString(e, e.mfjs_result_codes())).names,
          };
      })
    : Promise.reject(new Error('meshfix-wasm: WebAssembly is not available here'));
ready.catch(() => {}); // reported to whoever awaits it, never as an unhandled rejection

function instance() {
    if (wasm === null)
        throw new Error('meshfix-wasm: not ready yet; `await ready` before the first call');
    return wasm;
}

// Runs body(alloc) and frees everything alloc gave out, whatever happens.
function withHeap(body) {
    const { e } = instance();
    const taken = [];
    const alloc = (bytes) => {
        const pointer = e.mfjs_malloc(bytes) >>> 0;
        if (pointer === 0)
            throw new MeshfixError('MESHFIX_ERROR_OUT_OF_MEMORY', 'meshfix: out of memory (WebAssembly heap)');
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

function fail(e, status) {
    const code = wasm.results[status] || `MESHFIX_RESULT_${status}`;
    throw new MeshfixError(code, `meshfix: ${readString(e, e.mfjs_result_string(status))}`);
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

function requirementBits(requirements) {
    return flagBits(requirements, REQUIREMENTS, 'requirement');
}

// The C options, as the array of doubles src/meshfix_wasm.c reads.
function optionValues(e, alloc, options, index, position, triangleCount) {
    const { names, index: at } = wasm.options;
    const values = new Float64Array(names.length);
    const set = (name, value) => {
        if (!at.has(name))
            throw new Error(`meshfix-wasm: the WebAssembly has no option ${name} (a build from another version?)`);
        if (value !== undefined && value !== null)
            values[at.get(name)] = Number(value);
    };
    const evidence = options.evidence || {};
    const visibility = options.visibility || {};
    const policy = options.policy === undefined ? 0 : pick('policy', options.policy, POLICIES);
    if (policy === POLICIES.indexOf('sdf'))
        throw new TypeError('meshfix: policy "sdf" calls a C function for the distance; it is not available from JavaScript');
    set('indexSize', index.size);
    set('positionSize', position.size);
    set('topology', options.topology === undefined ? 0 : pick('topology', options.topology, TOPOLOGIES));
    set('weldTolerance', options.weldTolerance);
    set('policy', policy);
    upAxis(options.up).forEach((v, i) => set(`up.${i}`, v));
    set('seed', options.seed);
    set('evidence.sigma', evidence.sigma);
    set('evidence.minConfidence', evidence.minConfidence);
    const triangleNormals = normalData(evidence.triangleNormals, evidence.triangleNormalsStride, triangleCount, 'triangleNormals');
    if (triangleNormals !== null) {
        set('evidence.triangleNormals', copyIn(e, alloc, triangleNormals.data));
        set('evidence.triangleNormalsStride', triangleNormals.stride * 4);
    }
    const vertexNormals = normalData(evidence.vertexNormals, evidence.vertexNormalsStride, position.count, 'vertexNormals');
    if (vertexNormals !== null) {
        set('evidence.vertexNormals', copyIn(e, alloc, vertexNormals.data));
        set('evidence.vertexNormalsStride', vertexNormals.stride * 4);
    }
    set('visibility.rays', visibility.rays);
    set('visibility.minSamples', visibility.minSamples);
    set('visibility.coherenceDistance', visibility.coherenceDistance);
    set('visibility.c0', visibility.c0);
    set('visibility.eps', visibility.eps);
    set('visibility.kv', visibility.kv);
    set('visibility.flags', flagBits(visibility.flags, VISIBILITY_FLAGS, 'visibility flag'));
    return copyIn(e, alloc, values);
}

// A flat array of doubles into an object, "mesh.triangles" into mesh: { triangles }.
function unflatten(names, values, offset) {
    const out = {};
    names.forEach((name, i) => {
        const path = name.split('.');
        let node = out;
        for (let k = 0; k < path.length - 1; ++k)
            node = node[path[k]] = node[path[k]] || {};
        node[path[path.length - 1]] = values[offset + i];
    });
    return out;
}

function readReport(e, pointer) {
    const { names } = wasm.report;
    const report = unflatten(names, new Float64Array(e.memory.buffer, pointer, names.length), 0);
    report.verdict = VERDICTS[report.verdict] || String(report.verdict);
    return report;
}

function readComponents(e, pointer, count) {
    const { names } = wasm.component;
    const values = new Float64Array(e.memory.buffer, pointer, names.length * count);
    const components = [];
    for (let i = 0; i < count; ++i) {
        const c = unflatten(names, values, i * names.length);
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
        throw new MeshfixError('MESHFIX_ERROR_NOT_TRIANGLES', 'meshfix: index count is not a multiple of 3');
    const position = positionData(positions, index.data, options);
    const triangles = index.data.length / 3;
    return withHeap((alloc, e) => {
        const indexPointer = copyIn(e, alloc, index.data);
        const positionPointer = position.data === null ? 0 : copyIn(e, alloc, position.data);
        const optionPointer = optionValues(e, alloc, options, index, position, triangles);
        const reportPointer = alloc(8 * wasm.report.names.length);
        const summaryPointer = alloc(SUMMARY_BYTES);
        const flippedPointer = inspectOnly ? 0 : alloc(triangles);
        const patchPointer = alloc(4 * triangles);
        const confidencePointer = inspectOnly ? 0 : alloc(4 * triangles);
        const componentCapacity = options.components ? triangles : 0;
        const componentPointer = componentCapacity ? alloc(8 * wasm.component.names.length * componentCapacity) : 0;
        const out = copyIn(e, alloc, new Float64Array([
            reportPointer, summaryPointer, SUMMARY_BYTES, flippedPointer, patchPointer,
            confidencePointer, inspectOnly ? 0 : triangles, componentPointer, componentCapacity,
        ]));
        const stride = position.stride * position.size;
        const status = inspectOnly
            ? e.mfjs_inspect(indexPointer, index.data.length, positionPointer, position.count, stride, optionPointer, out)
            : e.mfjs_orient(indexPointer, indexPointer, index.data.length, positionPointer, position.count, stride,
                            optionPointer, out);
        if (status !== 0)
            fail(e, status);
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
    return withHeap((alloc, e) => {
        const indexPointer = copyIn(e, alloc, index.data);
        const positionPointer = position.data === null ? 0 : copyIn(e, alloc, position.data);
        const optionPointer = optionValues(e, alloc, options, index, position, Math.floor(index.data.length / 3));
        const failurePointer = alloc(8 * 6);
        const textPointer = alloc(CHECK_TEXT_BYTES);
        const ok = e.mfjs_check(indexPointer, index.data.length, positionPointer, position.count,
                                position.stride * position.size, requirementBits(requirements), optionPointer,
                                failurePointer, textPointer) !== 0;
        const f = new Float64Array(e.memory.buffer, failurePointer, 6);
        const requirement = Object.keys(REQUIREMENTS).find((name) => REQUIREMENTS[name] === f[1]);
        return {
            ok,
            text: readString(e, textPointer),
            result: wasm.results[f[0]] || `MESHFIX_RESULT_${f[0]}`,
            requirement: f[1] === 0 ? null : requirement || f[1],
            count: f[2],
            triangle: f[3] < 0 ? null : f[3],
            edge: f[4] < 0 ? null : [f[4], f[5]],
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
        const remapPointer = alloc(4 * position.count);
        const uniquePointer = alloc(8);
        const status = e.mfjs_weld(remapPointer, positionPointer, position.count, position.stride * position.size,
                                   tolerance || 0, position.size, uniquePointer);
        if (status !== 0)
            fail(e, status);
        return {
            remap: copyOut(e, Uint32Array, remapPointer, position.count),
            uniqueCount: new Float64Array(e.memory.buffer, uniquePointer, 1)[0],
        };
    });
}
