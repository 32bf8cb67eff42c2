// The glTF-Transform transform on the glTF 2.0 models of Debian's
// assimp-testmodels: some primitives of each model get a random half of
// their triangles reversed (a seeded stream: the same every run), then
//   - the flips equal those of meshfix.h built natively (test/native_orient.c)
//     on the same mesh-space triangles, positions and normals;
//   - the output document is the input with exactly those triangles
//     flipped, nothing else (positions, modes, untouched primitives);
//   - the Khronos glTF-Validator finds no error in the output that the
//     input did not have;
//   - a second run flips nothing.
//   node test/models.test.mjs NATIVE_BINARY [MODEL_DIRECTORY]
import { readdirSync, readFileSync, statSync } from 'node:fs';
import { dirname, join, relative } from 'node:path';
import { Logger, NodeIO } from '@gltf-transform/core';
import validator from 'gltf-validator';
import { meshfix } from '../dist/meshfix.mjs';
import { compareWithNative, drawnTriangles, failed, hash, isTriangleMode, newErrors, random, report, runNative, skip,
    validate } from './common.mjs';

const native = process.argv[2];
const modelRoot = process.argv[3] || '/usr/share/assimp/models/glTF2';

function findModels(directory) {
    const out = [];
    for (const name of readdirSync(directory).sort()) {
        const path = join(directory, name);
        if (statSync(path).isDirectory())
            out.push(...findModels(path));
        else if (/\.(gltf|glb)$/i.test(name))
            out.push(path);
    }
    return out;
}

function shuffleHalf(count, next) {
    const order = [...Array(count).keys()];
    for (let i = count - 1; i > 0; --i) {
        const j = Math.floor(next() * (i + 1));
        [order[i], order[j]] = [order[j], order[i]];
    }
    return new Set(order.slice(0, Math.floor(count / 2)));
}

// Reverses a random half of the triangles of some primitives (strips and
// fans: all of them, by restarting the strip one vertex later or reversing
// the fan). Returns { primitives, scrambled, reversed }.
function scramble(document, seed) {
    const next = random(seed);
    const stats = { primitives: 0, scrambled: 0, reversed: 0 };
    const done = new Set();
    const candidates = [];
    for (const mesh of document.getRoot().listMeshes())
        for (const primitive of mesh.listPrimitives())
            if (isTriangleMode(primitive.getMode()) && primitive.getAttribute('POSITION'))
                candidates.push(primitive);
    stats.primitives = candidates.length;
    const chosen = candidates.filter(() => next() < 0.5);
    if (chosen.length === 0 && candidates.length > 0)
        chosen.push(candidates[0]);
    for (const primitive of chosen) {
        const mode = primitive.getMode();
        const indices = primitive.getIndices();
        const count = primitive.getAttribute('POSITION').getCount();
        if (indices !== null && done.has(indices))
            continue;
        if (mode === 4 && indices !== null) {
            const array = indices.getArray().slice();
            const pick = shuffleHalf(Math.floor(array.length / 3), next);
            for (const t of pick)
                [array[3 * t + 1], array[3 * t + 2]] = [array[3 * t + 2], array[3 * t + 1]];
            indices.setArray(array);
            done.add(indices);
            stats.reversed += pick.size;
        } else if (mode === 4) {
            // not indexed: swap the vertices themselves, every attribute and morph target
            const pick = shuffleHalf(Math.floor(count / 3), next);
            const accessors = [...primitive.listAttributes(), ...primitive.listTargets().flatMap((t) => t.listAttributes())];
            for (const accessor of accessors) {
                if (done.has(accessor))
                    continue;
                done.add(accessor);
                const a = [], b = [];
                for (const t of pick) {
                    accessor.getElement(3 * t + 1, a);
                    accessor.getElement(3 * t + 2, b);
                    accessor.setElement(3 * t + 1, b);
                    accessor.setElement(3 * t + 2, a);
                }
            }
            stats.reversed += pick.size;
        } else {
            const v = indices !== null ? Array.from(indices.getArray()) : [...Array(count).keys()];
            const reversed = mode === 5 ? [v[0], ...v] : [v[0], ...v.slice(1).reverse()];
            const Type = indices !== null ? indices.getArray().constructor : Uint16Array;
            const accessor = document.createAccessor().setType('SCALAR').setArray(new Type(reversed))
                .setBuffer(document.getRoot().listBuffers()[0]);
            primitive.setIndices(accessor);
            if (indices !== null)
                done.add(indices);
            stats.reversed += v.length - 2;
        }
        stats.scrambled++;
    }
    return stats;
}

// Orientation of each triangle by its corners' positions, so that a
// winding can be compared across documents whatever the vertex order.
function windings(document) {
    const out = new Map();
    const ambiguous = new Set();
    for (const mesh of document.getRoot().listMeshes())
        mesh.listPrimitives().forEach((primitive) => {
            if (!isTriangleMode(primitive.getMode()))
                return;
            const position = primitive.getAttribute('POSITION');
            if (!position)
                return;
            const key = (v) => position.getElement(v, []).join(',');
            for (const [a, b, c] of drawnTriangles(primitive)) {
                const k = [key(a), key(b), key(c)];
                if (k[0] === k[1] || k[1] === k[2] || k[0] === k[2])
                    continue;
                const sorted = [...k].sort().join('|');
                const start = k.indexOf([...k].sort()[0]);
                const cyclic = [k[start], k[(start + 1) % 3], k[(start + 2) % 3]].join('|');
                if (out.has(sorted) && out.get(sorted) !== cyclic)
                    ambiguous.add(sorted);
                out.set(sorted, cyclic);
            }
        });
    for (const k of ambiguous)
        out.delete(k);
    return out;
}

// The output must be the input with exactly the reported flips applied.
function compareDocuments(input, output, captured) {
    const problems = [];
    const inMeshes = input.getRoot().listMeshes(), outMeshes = output.getRoot().listMeshes();
    if (inMeshes.length !== outMeshes.length)
        return [`${inMeshes.length} meshes in, ${outMeshes.length} out`];
    let primitivesChecked = 0;
    inMeshes.forEach((mesh, m) => {
        const inPrims = mesh.listPrimitives(), outPrims = outMeshes[m].listPrimitives();
        if (inPrims.length !== outPrims.length)
            return problems.push(`mesh ${m}: ${inPrims.length} primitives in, ${outPrims.length} out`);
        const info = captured.get(m);
        inPrims.forEach((inPrim, p) => {
            const outPrim = outPrims[p];
            const label = `mesh ${m} primitive ${p}`;
            const inPos = inPrim.getAttribute('POSITION'), outPos = outPrim.getAttribute('POSITION');
            if ((inPos === null) !== (outPos === null) ||
                (inPos && Buffer.compare(Buffer.from(inPos.getArray().buffer, inPos.getArray().byteOffset, inPos.getArray().byteLength),
                    Buffer.from(outPos.getArray().buffer, outPos.getArray().byteOffset, outPos.getArray().byteLength)) !== 0))
                problems.push(`${label}: POSITION changed`);
            const part = info && info.primitives.find((x) => x.index === p);
            const inTris = drawnTriangles(inPrim), outTris = drawnTriangles(outPrim);
            let expected = inTris, mode = inPrim.getMode();
            if (part) {
                primitivesChecked++;
                const flags = info.result.flipped.subarray(part.firstTriangle, part.firstTriangle + part.triangleCount);
                if (inTris.length !== part.triangleCount)
                    problems.push(`${label}: ${inTris.length} triangles drawn, the transform took ${part.triangleCount}`);
                if (flags.some((f) => f)) {
                    expected = [];
                    inTris.forEach(([a, b, c], t) => {
                        if (mode !== 4 && (a === b || b === c || a === c))
                            return;
                        expected.push(flags[t] ? [a, c, b] : [a, b, c]);
                    });
                    mode = 4;
                }
            }
            if (outPrim.getMode() !== mode)
                problems.push(`${label}: mode ${outPrim.getMode()}, expected ${mode}`);
            if (JSON.stringify(outTris) !== JSON.stringify(expected))
                problems.push(`${label}: triangles differ from the input with the library's flips applied`);
            const inIdx = inPrim.getIndices(), outIdx = outPrim.getIndices();
            if (inIdx && outIdx && inIdx.getComponentType() !== outIdx.getComponentType())
                problems.push(`${label}: index type ${inIdx.getComponentType()} became ${outIdx.getComponentType()}`);
        });
    });
    return { problems, primitivesChecked };
}

const io = new NodeIO().setLogger(new Logger(Logger.Verbosity.ERROR));
const quiet = (document) => document.setLogger(new Logger(Logger.Verbosity.ERROR));

// A document as .gltf JSON with its resources in memory (GLB holds one
// buffer only), the bytes the validator reads, and its externals.
async function serialize(document) {
    const { json, resources } = await io.writeJSON(document);
    return { json, resources, bytes: Buffer.from(JSON.stringify(json)) };
}

async function deserialize(file) {
    return quiet(await io.readJSON({ json: JSON.parse(JSON.stringify(file.json)), resources: { ...file.resources } }));
}

async function validateFile(file, uri) {
    return validate(validator, file.bytes, uri, null, (path) => file.resources[path]);
}
const totals = { models: 0, loaded: 0, primitives: 0, scrambled: 0, reversed: 0, meshes: 0, triangles: 0, flips: 0,
    restored: 0, restorable: 0, inputErrors: 0, outputErrors: 0, originalErrors: 0, skippedPrimitives: 0 };
const notLoaded = [];
const models = findModels(modelRoot);
if (models.length === 0)
    skip('glTF models', `none under ${modelRoot} (Debian: apt-get install assimp-testmodels)`);

for (const path of models) {
    const name = relative(modelRoot, path);
    totals.models++;
    let original;
    try {
        original = quiet(await io.read(path));
    } catch (error) {
        notLoaded.push(`${name} (${error.message.split('\n')[0]})`);
        skip(name, `glTF-Transform cannot read it: ${error.message.split('\n')[0]}`);
        continue;
    }
    totals.loaded++;
    const before = windings(original);
    const originalCheck = await validate(validator, readFileSync(path), name, dirname(path));
    const stats = scramble(original, hash(name));
    const scrambled = await serialize(original);
    const inputCheck = await validateFile(scrambled, name);
    const input = await deserialize(scrambled);
    const reference = await deserialize(scrambled);

    const captured = new Map();
    let gltfReport = null;
    await input.transform(meshfix({ onMesh: (m) => captured.set(m.meshIndex, m), onReport: (r) => (gltfReport = r) }));
    const written = await serialize(input);
    const outputCheck = await validateFile(written, name);
    const output = await deserialize(written);

    // 1. the native library on the same arrays
    const meshes = [...captured.values()];
    const nativeResults = native ? runNative(native, meshes.map((m) => ({
        indices: m.indices, positions: m.positions, normals: m.vertexNormals, policy: 'auto' })), 'models_native') : [];
    const flipProblems = [];
    let triangles = 0, flips = 0;
    meshes.forEach((m, i) => {
        flipProblems.push(...compareWithNative(m.result, nativeResults[i], `mesh ${m.meshIndex}`));
        triangles += m.result.flipped.length;
        flips += m.result.report.trianglesFlipped;
    });
    if (flips !== gltfReport.trianglesFlipped)
        flipProblems.push(`report.trianglesFlipped ${gltfReport.trianglesFlipped}, meshes flipped ${flips}`);
    report(`${name}: same flips as the C library (${meshes.length} meshes, ${triangles} triangles, ${flips} flipped)`,
        native && flipProblems.length === 0, native ? flipProblems.join('\n') : 'no native build');

    // 2. the output is the input with exactly those flips
    const compared = compareDocuments(reference, output, captured);
    report(`${name}: output = input with those flips (${compared.primitivesChecked} of ${stats.primitives} triangle primitives, ` +
        `${stats.scrambled} scrambled)`, compared.problems.length === 0, compared.problems.join('\n'));

    // 3. validator: no new errors
    const added = newErrors(inputCheck, outputCheck);
    report(`${name}: glTF-Validator, no new errors (original file ${originalCheck.numErrors}, scrambled input ` +
        `${inputCheck.numErrors}, output ${outputCheck.numErrors})`, added.length === 0, added.join('\n'));

    // 4. idempotent
    let again = null;
    await output.transform(meshfix({ onReport: (r) => (again = r) }));
    report(`${name}: a second run flips nothing`, again.trianglesFlipped === 0, again.summary);

    const after = windings(output);
    let restorable = 0, restored = 0;
    for (const [key, winding] of before)
        if (after.has(key)) {
            restorable++;
            if (after.get(key) === winding)
                restored++;
        }
    if (restored < restorable)
        console.log(`    ${name}: ${restorable - restored} of ${restorable} triangles wound unlike the original file after the repair`);
    totals.restorable += restorable;
    totals.restored += restored;
    totals.primitives += stats.primitives;
    totals.scrambled += stats.scrambled;
    totals.reversed += stats.reversed;
    totals.meshes += meshes.length;
    totals.triangles += triangles;
    totals.flips += flips;
    totals.skippedPrimitives += gltfReport.skipped.length;
    totals.originalErrors += originalCheck.numErrors;
    totals.inputErrors += inputCheck.numErrors;
    totals.outputErrors += outputCheck.numErrors;
}

console.log(`    models: ${totals.models} found, ${totals.loaded} read by glTF-Transform (not read: ${notLoaded.length})`);
console.log(`    triangle primitives: ${totals.primitives}, ${totals.scrambled} scrambled (${totals.reversed} triangles reversed), ` +
    `${totals.skippedPrimitives} skipped by the transform`);
console.log(`    meshes: ${totals.meshes}; triangles compared with the native build: ${totals.triangles}, flipped: ${totals.flips}`);
console.log(`    winding as in the original file after the repair: ${totals.restored} of ${totals.restorable} triangles ` +
    `(${(100 * totals.restored / Math.max(totals.restorable, 1)).toFixed(2)}%)`);
console.log(`    validator errors: original files ${totals.originalErrors}, scrambled inputs ${totals.inputErrors}, ` +
    `outputs ${totals.outputErrors}`);
console.log(`models: ${failed()} failed`);
process.exit(failed() ? 1 : 0);
