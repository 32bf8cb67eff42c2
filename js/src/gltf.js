// The glTF-Transform transform. A fragment after src/api.js (see
// scripts/build.mjs): it uses orient() and ready from there, and nothing
// from @gltf-transform/core at run time, only the Document it is given.
//
// Per mesh, in mesh space: the triangles of all its triangle primitives
// (modes 4, 5, 6; strips and fans expanded as the glTF spec draws them)
// are concatenated over their positions and oriented together, so a
// closed model split into primitives by material is one closed shell.
// Each primitive then gets its own indices back:
//   TRIANGLES, indexed       the index accessor rewritten (cloned first
//                            when anything else uses it);
//   TRIANGLES, not indexed   an index accessor created, only when a
//                            triangle flips;
//   STRIP, FAN               rewritten as a TRIANGLES list, only when a
//                            triangle flips (triangles that repeat an
//                            index, which draw nothing, are left out).
// Nodes whose world transform mirrors (negative determinant: the spec
// reverses their winding) and double-sided materials are reported, never
// changed; NORMAL is evidence for the decision.

const GLTF_TRIANGLES = 4;
const GLTF_TRIANGLE_STRIP = 5;
const GLTF_TRIANGLE_FAN = 6;
const GLTF_MODE_NAMES = { 4: 'TRIANGLES', 5: 'TRIANGLE_STRIP', 6: 'TRIANGLE_FAN' };
const GLTF_COMPRESSION = ['KHR_draco_mesh_compression', 'EXT_meshopt_compression'];

// The triangles of a primitive as a list of local vertex indices, in the
// order and winding the glTF spec (3.7.2.1) draws them.
function gltfTriangles(mode, vertices, count) {
    const at = vertices === null ? (i) => i : (i) => vertices[i];
    let triangles;
    if (mode === GLTF_TRIANGLES) {
        triangles = new Uint32Array(count - (count % 3));
        for (let i = 0; i < triangles.length; ++i)
            triangles[i] = at(i);
    } else {
        const n = Math.max(count - 2, 0);
        triangles = new Uint32Array(3 * n);
        for (let i = 0; i < n; ++i) {
            if (mode === GLTF_TRIANGLE_STRIP) { // p_i = {v_i, v_(i+1+i%2), v_(i+2-i%2)}
                triangles[3 * i] = at(i);
                triangles[3 * i + 1] = at(i + 1 + (i % 2));
                triangles[3 * i + 2] = at(i + 2 - (i % 2));
            } else { // fan: p_i = {v_(i+1), v_(i+2), v_0}
                triangles[3 * i] = at(i + 1);
                triangles[3 * i + 1] = at(i + 2);
                triangles[3 * i + 2] = at(0);
            }
        }
    }
    return triangles;
}

// x y z of every element of an accessor as floats (normalized integers
// as the spec decodes them).
function gltfVectors(accessor) {
    const count = accessor.getCount();
    const array = accessor.getArray();
    if (array instanceof Float32Array && accessor.getElementSize() === 3 && array.length === 3 * count)
        return array;
    const out = new Float32Array(3 * count);
    const element = [];
    for (let i = 0; i < count; ++i) {
        accessor.getElement(i, element);
        out[3 * i] = element[0];
        out[3 * i + 1] = element[1];
        out[3 * i + 2] = element[2];
    }
    return out;
}

function gltfMirrors(node) {
    const m = node.getWorldMatrix(); // column-major 4x4; the sign of the 3x3 part
    return m[0] * (m[5] * m[10] - m[6] * m[9]) - m[4] * (m[1] * m[10] - m[2] * m[9]) + m[8] * (m[1] * m[6] - m[2] * m[5]);
}

function gltfIndexType(vertexCount) {
    return vertexCount <= 0xffff ? Uint16Array : Uint32Array; // 0xffff itself is the restart value
}

function gltfName(property, fallback) {
    const name = property.getName();
    return name !== '' ? name : fallback;
}

// True when something besides primitive's use of it as indices holds the accessor.
function gltfShared(accessor, primitive, root) {
    const users = accessor.listParents().filter((p) => p !== root);
    return users.length !== 1 || users[0] !== primitive || primitive.listAttributes().includes(accessor) ||
        primitive.listTargets().some((target) => target.listAttributes().includes(accessor));
}

// The triangle primitives of a mesh and their mesh-space triangles;
// primitives that cannot be read go to `skipped`.
function gltfCollect(mesh, meshIndex, report) {
    const parts = [];
    mesh.listPrimitives().forEach((primitive, primitiveIndex) => {
        const mode = primitive.getMode();
        if (!(mode in GLTF_MODE_NAMES))
            return;
        const skip = (reason) => report.skipped.push({ mesh: meshIndex, primitive: primitiveIndex, reason });
        const position = primitive.getAttribute('POSITION');
        if (position === null)
            return skip('no POSITION attribute');
        if (position.getElementSize() !== 3)
            return skip('POSITION is not a 3-component vector');
        if (position.getArray() === null)
            return skip('POSITION has no data');
        const indices = primitive.getIndices();
        const vertexCount = position.getCount();
        const list = indices === null ? null : indices.getArray();
        if (indices !== null && list === null)
            return skip('the index accessor has no data');
        if (list !== null && !(list instanceof Uint8Array || list instanceof Uint16Array || list instanceof Uint32Array))
            return skip(`indices of component type ${indices.getComponentType()} (not an unsigned integer)`);
        const triangles = gltfTriangles(mode, list, list === null ? vertexCount : list.length);
        for (let i = 0; i < triangles.length; ++i)
            if (triangles[i] >= vertexCount)
                return skip(`index ${triangles[i]} is out of range (${vertexCount} vertices)`);
        const normal = primitive.getAttribute('NORMAL');
        parts.push({
            primitive, primitiveIndex, mode, indices, position,
            normal: normal !== null && normal.getArray() !== null && normal.getElementSize() === 3 &&
            normal.getCount() === vertexCount ? normal : null,
            triangles,
        });
    });
    return parts;
}

// One mesh's arrays for orient(): positions (and normals) of every vertex
// block once, triangles with each block's offset.
function gltfMeshArrays(parts, useNormals) {
    const blocks = new Map();
    let vertexCount = 0, indexCount = 0, anyNormals = false;
    for (const part of parts) {
        const normal = useNormals ? part.normal : null;
        let block = blocks.get(part.position);
        if (block === undefined)
            blocks.set(part.position, block = new Map());
        if (!block.has(normal)) {
            block.set(normal, vertexCount);
            vertexCount += part.position.getCount();
        }
        part.base = block.get(normal);
        part.firstTriangle = indexCount / 3;
        indexCount += part.triangles.length;
        anyNormals = anyNormals || normal !== null;
    }
    const positions = new Float32Array(3 * vertexCount);
    const normals = anyNormals ? new Float32Array(3 * vertexCount) : null; // zero: no evidence
    for (const [position, block] of blocks) {
        for (const [normal, base] of block) {
            positions.set(gltfVectors(position), 3 * base);
            if (normal !== null)
                normals.set(gltfVectors(normal), 3 * base);
        }
    }
    const indices = new Uint32Array(indexCount);
    for (const part of parts)
        for (let i = 0; i < part.triangles.length; ++i)
            indices[3 * part.firstTriangle + i] = part.triangles[i] + part.base;
    return { positions, normals, indices };
}

// Writes a primitive's repaired triangles; returns what was done.
function gltfWrite(document, part, flipped, count) {
    const root = document.getRoot();
    const { primitive, mode, indices, position, triangles } = part;
    const first = part.firstTriangle;
    const vertexCount = position.getCount();
    const flip = (out, t) => {
        const b = out[3 * t + 1];
        out[3 * t + 1] = out[3 * t + 2];
        out[3 * t + 2] = b;
    };
    const buffer = () => position.getBuffer() || root.listBuffers()[0] || document.createBuffer();
    if (mode === GLTF_TRIANGLES && indices !== null) {
        const out = indices.getArray().slice();
        for (let t = 0; t < triangles.length / 3; ++t)
            if (flipped[first + t])
                flip(out, t);
        if (gltfShared(indices, primitive, root)) {
            primitive.setIndices(indices.clone().setArray(out));
            count.accessorsCloned++;
            return 'indices cloned and rewritten';
        }
        indices.setArray(out);
        return 'indices rewritten';
    }
    let out;
    if (mode === GLTF_TRIANGLES) {
        out = new (gltfIndexType(vertexCount))(triangles);
        for (let t = 0; t < triangles.length / 3; ++t)
            if (flipped[first + t])
                flip(out, t);
    } else {
        const kept = [];
        for (let t = 0; t < triangles.length / 3; ++t) {
            const a = triangles[3 * t], b = triangles[3 * t + 1], c = triangles[3 * t + 2];
            if (a === b || b === c || a === c)
                continue; // draws nothing (a strip's stitch)
            if (flipped[first + t])
                kept.push(a, c, b);
            else
                kept.push(a, b, c);
        }
        const Type = indices !== null ? indices.getArray().constructor : gltfIndexType(vertexCount);
        out = new Type(kept);
    }
    const created = document.createAccessor(indices !== null ? indices.getName() : '')
        .setType('SCALAR')
        .setArray(out)
        .setBuffer(indices !== null && indices.getBuffer() !== null ? indices.getBuffer() : buffer());
    primitive.setIndices(created);
    count.accessorsCreated++;
    if (mode !== GLTF_TRIANGLES) {
        primitive.setMode(GLTF_TRIANGLES);
        count.primitivesConverted++;
    }
    if (indices !== null && indices.listParents().every((p) => p === root)) {
        indices.dispose();
        count.accessorsRemoved++;
    }
    return mode === GLTF_TRIANGLES ? 'indices created' : `${GLTF_MODE_NAMES[mode]} rewritten as TRIANGLES`;
}

function gltfCount(n, one, many) {
    return `${n} ${n === 1 ? one : many}`;
}

function gltfSummary(r) {
    const meshes = r.meshes.filter((m) => m.triangles > 0).length;
    const line = r.trianglesFlipped === 0
        ? `clean: nothing to flip (${gltfCount(r.triangles, 'triangle', 'triangles')}, ${gltfCount(meshes, 'mesh', 'meshes')})`
        : `${r.dryRun ? 'would fix' : 'fixed'} ${gltfCount(r.trianglesFlipped, 'triangle', 'triangles')} in ` +
          `${r.meshesChanged} of ${gltfCount(meshes, 'mesh', 'meshes')} (${gltfCount(r.primitivesChanged, 'primitive', 'primitives')})`;
    const notes = [];
    const failed = r.meshes.filter((m) => m.error !== undefined).length;
    if (failed)
        notes.push(`${gltfCount(failed, 'mesh', 'meshes')} refused`);
    const doubtful = r.meshes.filter((m) => m.verdict === 'doubtful').length;
    if (doubtful)
        notes.push(`${gltfCount(doubtful, 'mesh', 'meshes')} doubtful (no clear evidence for some parts)`);
    if (r.skipped.length)
        notes.push(`${gltfCount(r.skipped.length, 'primitive', 'primitives')} skipped`);
    if (r.mirroredNodes.length)
        notes.push(`${gltfCount(r.mirroredNodes.length, 'mirrored node', 'mirrored nodes')}`);
    if (r.doubleSidedMaterials.length)
        notes.push(`${gltfCount(r.doubleSidedMaterials.length, 'double-sided material', 'double-sided materials')}`);
    return notes.length ? `${line}; ${notes.join(', ')}` : line;
}

// The transform's options: orient's, less those of one call's arrays (the
// normals are each mesh's NORMAL), and its own.
const GLTF_OPTIONS = { normals: takeBoolean, dryRun: takeBoolean, onReport: takeFunction, onMesh: takeFunction };
const GLTF_NOT_OPTIONS = ['evidence.triangleNormals', 'evidence.triangleNormalsStride', 'evidence.vertexNormals',
    'evidence.vertexNormalsStride'];
let gltfSchema = null;

function meshfix(options) {
    options = options || {};
    const transform = async function meshfixTransform(document) {
        await ready;
        // refused before any mesh, as orient would refuse them for every mesh
        gltfSchema = gltfSchema || optionSchema(instance().layout, GLTF_OPTIONS, GLTF_NOT_OPTIONS);
        takeOptions(options, gltfSchema);
        const root = document.getRoot();
        const logger = document.getLogger();
        const compressed = root.listExtensionsUsed().map((e) => e.extensionName).filter((n) => GLTF_COMPRESSION.includes(n));
        const report = {
            dryRun: !!options.dryRun,
            triangles: 0, trianglesFlipped: 0, meshesChanged: 0, primitivesChanged: 0,
            accessorsCloned: 0, accessorsCreated: 0, accessorsRemoved: 0, primitivesConverted: 0,
            meshes: [], primitives: [], skipped: [], mirroredNodes: [], doubleSidedMaterials: [],
            compression: compressed, summary: '',
        };
        const orientOptions = { ...options };
        for (const key of ['normals', 'dryRun', 'onReport', 'onMesh'])
            delete orientOptions[key];
        if (orientOptions.policy === 'up' && orientOptions.up === undefined)
            orientOptions.up = 'y'; // glTF is +Y up
        const flippedByPrimitive = new Map();
        root.listMeshes().forEach((mesh, meshIndex) => {
            const parts = gltfCollect(mesh, meshIndex, report);
            const entry = { index: meshIndex, name: mesh.getName(), primitives: parts.length, triangles: 0, trianglesFlipped: 0 };
            report.meshes.push(entry);
            if (parts.length === 0)
                return;
            const arrays = gltfMeshArrays(parts, options.normals !== false);
            const callOptions = { ...orientOptions };
            if (arrays.normals !== null)
                callOptions.evidence = { ...(orientOptions.evidence || {}), vertexNormals: arrays.normals };
            entry.triangles = arrays.indices.length / 3;
            report.triangles += entry.triangles;
            let result;
            try {
                result = orient(arrays.indices, arrays.positions, callOptions);
            } catch (error) {
                // an option the library refuses (rays above its limit, ...) is refused for every mesh: so is the transform
                if (!(error instanceof MeshfixError) || error.code === 'MESHFIX_ERROR_INVALID_ARGUMENT')
                    throw error;
                entry.error = error.message;
                logger.warn(`meshfix: mesh "${gltfName(mesh, meshIndex)}" left as it is: ${error.message}`);
                return;
            }
            entry.trianglesFlipped = result.report.trianglesFlipped;
            entry.verdict = result.report.verdict;
            entry.summary = result.summary;
            entry.report = result.report;
            if (options.onMesh)
                options.onMesh({
                    mesh, meshIndex, indices: arrays.indices, positions: arrays.positions, vertexNormals: arrays.normals,
                    options: callOptions, result,
                    primitives: parts.map((p) => ({
                        primitive: p.primitive, index: p.primitiveIndex, mode: p.mode,
                        firstTriangle: p.firstTriangle, triangleCount: p.triangles.length / 3,
                    })),
                });
            report.trianglesFlipped += entry.trianglesFlipped;
            if (entry.trianglesFlipped > 0)
                report.meshesChanged++;
            for (const part of parts) {
                let flips = 0;
                for (let t = 0; t < part.triangles.length / 3; ++t)
                    flips += result.flipped[part.firstTriangle + t];
                const line = {
                    mesh: meshIndex, primitive: part.primitiveIndex, mode: GLTF_MODE_NAMES[part.mode],
                    indices: part.indices === null ? null : 8 * part.indices.getArray().BYTES_PER_ELEMENT,
                    triangles: part.triangles.length / 3, trianglesFlipped: flips, action: 'unchanged',
                };
                flippedByPrimitive.set(part.primitive, (flippedByPrimitive.get(part.primitive) || 0) + flips);
                if (flips > 0) {
                    report.primitivesChanged++;
                    line.action = options.dryRun ? 'would change' : gltfWrite(document, part, result.flipped, report);
                }
                report.primitives.push(line);
            }
            logger.debug(`meshfix: mesh "${gltfName(mesh, meshIndex)}": ${result.summary}`);
        });
        root.listNodes().forEach((node, index) => {
            const mesh = node.getMesh();
            if (mesh === null)
                return;
            const determinant = gltfMirrors(node);
            if (determinant < 0)
                report.mirroredNodes.push({
                    index, name: node.getName(), mesh: root.listMeshes().indexOf(mesh), determinant,
                });
        });
        root.listMaterials().forEach((material, index) => {
            if (!material.getDoubleSided())
                return;
            const users = material.listParents().filter((p) => flippedByPrimitive.has(p));
            if (users.length === 0)
                return;
            report.doubleSidedMaterials.push({
                index, name: material.getName(), primitives: users.length,
                primitivesFlipped: users.filter((p) => flippedByPrimitive.get(p) > 0).length,
            });
        });
        report.summary = gltfSummary(report);
        // said once: to onReport when given (the logger has it at debug
        // level), else through the logger at info level
        const say = options.onReport ? (text) => logger.debug(text) : (text) => logger.info(text);
        say(`meshfix: ${report.summary}`);
        for (const node of report.mirroredNodes)
            say(`meshfix: node "${gltfName(root.listNodes()[node.index], node.index)}" mirrors its mesh (determinant ${node.determinant.toPrecision(3)}): renderers reverse its winding, as the spec says; left as it is`);
        if (options.onReport)
            options.onReport(report);
    };
    Object.defineProperty(transform, 'name', { value: 'meshfix' }); // as glTF-Transform's createTransform names it
    return transform;
}
