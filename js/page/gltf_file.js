// The page's glTF: a .glb (or a .gltf with its buffers embedded or dropped
// beside it) read by glTF-Transform's WebIO and repaired by the package's
// own transform (meshfix() of src/gltf.js, in meshfix.mjs).
//
// The transform runs as a dry run and hands over, per mesh, the triangles
// it oriented and which of them flip (onMesh). A .glb whose flipped
// triangles all sit in index accessors of its BIN chunk that only their
// primitive uses (the common case) is then written as the command-line tool
// writes it: the same bytes with the second and third index of each flipped
// triangle swapped. Anything else (strips, fans, shared or missing index
// accessors, a .gltf) is written by the transform itself through
// glTF-Transform, as a .glb.
import { Logger, WebIO } from './vendor/gltf-transform-core.js';
import { meshfix, ready } from './meshfix.mjs';

const GLB_MAGIC = 0x46546c67; // 'glTF'
const CHUNK_JSON = 0x4e4f534a;
const CHUNK_BIN = 0x004e4942;
const COMPONENT_BYTES = { 5121: 1, 5123: 2, 5125: 4 };

// A .glb's JSON and where its BIN chunk's bytes start, or null.
export function glbChunks(bytes) {
    if (bytes.length < 20)
        return null;
    const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
    if (view.getUint32(0, true) !== GLB_MAGIC || view.getUint32(4, true) !== 2)
        return null;
    const jsonLength = view.getUint32(12, true);
    if (view.getUint32(16, true) !== CHUNK_JSON || 20 + jsonLength > bytes.length)
        return null;
    const json = JSON.parse(new TextDecoder().decode(bytes.subarray(20, 20 + jsonLength)));
    let bin = null, binLength = 0;
    const at = 20 + jsonLength;
    if (at + 8 <= bytes.length && view.getUint32(at + 4, true) === CHUNK_BIN) {
        bin = at + 8;
        binLength = view.getUint32(at, true);
    }
    return { json, bin, binLength };
}

// Where primitive (mesh, primitive)'s indices are in the file, when a
// rewrite in place is what the command-line tool does there: a triangle list
// whose index accessor is in the BIN chunk, tightly packed, and used by no
// other primitive or attribute. Otherwise null.
function inPlaceIndices(chunks, mesh, primitive) {
    const { json, bin, binLength } = chunks;
    const p = json.meshes[mesh].primitives[primitive];
    if ((p.mode === undefined ? 4 : p.mode) !== 4 || p.indices === undefined || bin === null)
        return null;
    const uses = [];
    for (const m of json.meshes)
        for (const q of m.primitives) {
            if (q.indices === p.indices)
                uses.push(q);
            for (const a of Object.values(q.attributes || {}))
                if (a === p.indices)
                    uses.push(null);
            for (const t of q.targets || [])
                for (const a of Object.values(t))
                    if (a === p.indices)
                        uses.push(null);
        }
    const accessor = json.accessors[p.indices];
    if (uses.length !== 1 || accessor.bufferView === undefined || accessor.sparse !== undefined)
        return null;
    const view = json.bufferViews[accessor.bufferView];
    const size = COMPONENT_BYTES[accessor.componentType];
    if (size === undefined || view.buffer !== 0 || json.buffers[0].uri !== undefined ||
        (view.byteStride !== undefined && view.byteStride !== size))
        return null;
    const offset = (view.byteOffset || 0) + (accessor.byteOffset || 0);
    if (offset + size * accessor.count > Math.min(binLength, (view.byteOffset || 0) + view.byteLength))
        return null;
    return { at: bin + offset, size, count: accessor.count };
}

function swapElements(bytes, at, size, i, j) {
    for (let k = 0; k < size; ++k) {
        const b = bytes[at + size * i + k];
        bytes[at + size * i + k] = bytes[at + size * j + k];
        bytes[at + size * j + k] = b;
    }
}

// Resources dropped beside a .gltf (name -> bytes) and the .gltf itself.
async function readDocument(io, name, bytes, resources) {
    if (/\.glb$/i.test(name) || glbChunks(bytes) !== null)
        return io.readBinary(bytes);
    const json = JSON.parse(new TextDecoder().decode(bytes));
    const found = {};
    for (const b of json.buffers || [])
        if (b.uri !== undefined && !b.uri.startsWith('data:')) {
            const file = resources.get(decodeURIComponent(b.uri).split('/').pop());
            if (file === undefined)
                throw new Error(`${name} needs ${b.uri}: drop it together with the .gltf`);
            found[b.uri] = file;
        }
    for (const image of json.images || [])
        if (image.uri !== undefined && !image.uri.startsWith('data:')) {
            const file = resources.get(decodeURIComponent(image.uri).split('/').pop());
            found[image.uri] = file || new Uint8Array(0); // never decoded
        }
    return io.readJSON({ json, resources: found });
}

// The triangles to draw: every node's mesh in world space (what a viewer
// shows), with each triangle's flag from the repair.
function drawable(document, meshes) {
    const byMesh = new Map(meshes.map((m) => [m.mesh, m]));
    const parts = [];
    for (const node of document.getRoot().listNodes()) {
        const mesh = node.getMesh();
        const entry = mesh && byMesh.get(mesh);
        if (!entry)
            continue;
        const m = node.getWorldMatrix();
        const p = entry.positions;
        const world = new Float32Array(p.length);
        for (let v = 0; v < p.length; v += 3) {
            const x = p[v], y = p[v + 1], z = p[v + 2];
            world[v] = m[0] * x + m[4] * y + m[8] * z + m[12];
            world[v + 1] = m[1] * x + m[5] * y + m[9] * z + m[13];
            world[v + 2] = m[2] * x + m[6] * y + m[10] * z + m[14];
        }
        const det = m[0] * (m[5] * m[10] - m[6] * m[9]) - m[4] * (m[1] * m[10] - m[2] * m[9]) +
            m[8] * (m[1] * m[6] - m[2] * m[5]);
        parts.push({ positions: world, indices: entry.indices, flipped: entry.flipped, mirrored: det < 0 });
    }
    return parts;
}

// Repairs a glTF; returns { output, outputName, summary, lines, parts, byteExact }.
export async function repairGltf(name, bytes, resources = new Map()) {
    await ready;
    const io = new WebIO();
    const document = await readDocument(io, name, bytes, resources);
    document.setLogger(new Logger(Logger.Verbosity.WARN)); // the page shows the summary itself
    const meshes = [];
    let report = null;
    await document.transform(meshfix({
        dryRun: true,
        onReport: (r) => (report = r),
        onMesh: (m) => meshes.push({
            mesh: m.mesh, meshIndex: m.meshIndex, indices: m.indices, positions: m.positions,
            flipped: m.result.flipped, primitives: m.primitives, report: m.result.report, summary: m.result.summary,
        }),
    }));
    const flips = meshes.reduce((s, m) => s + m.report.trianglesFlipped, 0);
    const chunks = glbChunks(bytes);
    const stem = name.replace(/\.(glb|gltf)$/i, '');
    let output = null, byteExact = false;
    if (chunks !== null) {
        // the command-line tool's way: the same bytes, flipped triangles' corners swapped in place
        output = new Uint8Array(bytes);
        for (const m of meshes) {
            for (const p of m.primitives) {
                let any = false;
                for (let t = 0; t < p.triangleCount && !any; ++t)
                    any = m.flipped[p.firstTriangle + t] !== 0;
                if (!any)
                    continue;
                const place = inPlaceIndices(chunks, m.meshIndex, p.index);
                if (place === null || place.count !== 3 * p.triangleCount) {
                    output = null;
                    break;
                }
                for (let t = 0; t < p.triangleCount; ++t)
                    if (m.flipped[p.firstTriangle + t])
                        swapElements(output, place.at, place.size, 3 * t + 1, 3 * t + 2);
            }
            if (output === null)
                break;
        }
        byteExact = output !== null;
    }
    if (output === null) {
        // strips, fans, shared accessors, a .gltf: the transform writes the document
        const again = await readDocument(io, name, bytes, resources);
        again.setLogger(new Logger(Logger.Verbosity.WARN));
        await again.transform(meshfix());
        output = await io.writeBinary(again);
    }
    const lines = meshes.map((m) => `mesh ${m.meshIndex}${m.mesh.getName() ? ` '${m.mesh.getName()}'` : ''}: ` +
        `${m.summary} (${m.report.mesh.triangles} triangles, verdict ${m.report.verdict})`);
    return {
        output, outputName: `${stem}.fixed.glb`, summary: report.summary.replace(/^would fix/, 'fixed'), flips,
        triangles: report.triangles, lines, parts: drawable(document, meshes), byteExact,
    };
}
