// The glTF-Transform transform on documents built here, where every
// answer is known: one cube mesh of six primitives in every form the
// transform writes (8-, 16- and 32-bit indices, not indexed, strip, fan,
// an index accessor shared with another mesh), five of its faces reversed;
// a correct cube of strips and fans; an open sheet whose NORMAL says which
// way it faces; a mirrored node and a double-sided material.
//   node test/transform.test.mjs NATIVE_BINARY
import { Document, Logger, NodeIO } from '@gltf-transform/core';
import validator from 'gltf-validator';
import { meshfix, MeshfixError } from '../dist/meshfix.mjs';
import { compareWithNative, drawnTriangles, failed, headerResults, runNative, test, validate } from './common.mjs';

const native = process.argv[2];
const io = new NodeIO().setLogger(new Logger(Logger.Verbosity.ERROR));

// unit cube corner v = x + 2y + 4z; faces as outward quads (a, b, c, d)
const CORNERS = [0, 1, 2, 3, 4, 5, 6, 7].flatMap((v) => [v & 1, (v >> 1) & 1, (v >> 2) & 1]);
const FACES = { zMin: [0, 2, 3, 1], zMax: [4, 5, 7, 6], yMin: [0, 1, 5, 4], yMax: [2, 6, 7, 3], xMin: [0, 4, 6, 2], xMax: [1, 3, 7, 5] };
const quadTriangles = ([a, b, c, d], reversed) => (reversed ? [a, c, b, a, d, c] : [a, b, c, a, c, d]);
const cornerPositions = (list) => new Float32Array(list.flatMap((v) => CORNERS.slice(3 * v, 3 * v + 3)));

function build() {
    const document = new Document();
    document.setLogger(new Logger(Logger.Verbosity.ERROR));
    const buffer = document.createBuffer();
    const accessor = (array, type) => document.createAccessor().setType(type).setArray(array).setBuffer(buffer);
    const corners = accessor(new Float32Array(CORNERS), 'VEC3');
    const primitive = (position, indices, mode) => {
        const p = document.createPrimitive().setAttribute('POSITION', position).setMode(mode);
        if (indices)
            p.setIndices(indices);
        return p;
    };
    const doubleSided = document.createMaterial('double-sided').setDoubleSided(true);

    const cube = document.createMesh('cube');
    const lidIndices = accessor(new Uint16Array(quadTriangles(FACES.zMax, true)), 'SCALAR');
    cube.addPrimitive(primitive(corners, accessor(new Uint8Array(quadTriangles(FACES.zMin, true)), 'SCALAR'), 4)
        .setMaterial(doubleSided));                                                            // A: 8-bit, reversed
    cube.addPrimitive(primitive(corners, lidIndices, 4));                                      // B: 16-bit, shared, reversed
    cube.addPrimitive(primitive(corners, accessor(new Uint32Array(quadTriangles(FACES.yMin)), 'SCALAR'), 4)); // C: right
    const [a, b, c, d] = FACES.yMax;
    cube.addPrimitive(primitive(accessor(cornerPositions([a, c, b, a, d, c]), 'VEC3'), null, 4)); // D: not indexed, reversed
    const x = FACES.xMin;
    cube.addPrimitive(primitive(accessor(cornerPositions([x[1], x[0], x[2], x[3]]), 'VEC3'), null, 5)); // E: strip, reversed
    const f = FACES.xMax;
    cube.addPrimitive(primitive(corners, accessor(new Uint16Array([f[0], f[3], f[2], f[1]]), 'SCALAR'), 6)); // F: fan, reversed

    const lid = document.createMesh('lid').addPrimitive(primitive(corners, lidIndices, 4));

    // a right cube of strips and fans: left as it is
    const good = document.createMesh('good');
    for (const [name, q] of Object.entries(FACES)) {
        if (name.startsWith('x'))
            good.addPrimitive(primitive(corners, accessor(new Uint16Array(q), 'SCALAR'), 6));
        else
            good.addPrimitive(primitive(corners, accessor(new Uint16Array([q[1], q[2], q[0], q[3]]), 'SCALAR'), 5));
    }

    // an open quad in y = 0 wound to face -y, its NORMAL +y
    const sheetPositions = accessor(new Float32Array([0, 0, 0, 1, 0, 0, 1, 0, 1, 0, 0, 1]), 'VEC3');
    const sheet = document.createMesh('sheet').addPrimitive(primitive(sheetPositions, accessor(new Uint16Array([0, 1, 2, 0, 2, 3]), 'SCALAR'), 4)
        .setAttribute('NORMAL', accessor(new Float32Array([0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0]), 'VEC3')));

    const mirror = document.createNode('mirror').setMesh(cube).setScale([-1, 1, 1]);
    mirror.addChild(document.createNode('mirrored child').setMesh(good).setTranslation([3, 0, 0]));
    const scene = document.createScene().addChild(mirror)
        .addChild(document.createNode('lid').setMesh(lid).setTranslation([0, 3, 0]))
        .addChild(document.createNode('sheet').setMesh(sheet).setTranslation([0, -3, 0]));
    document.getRoot().setDefaultScene(scene);
    return document;
}

async function run(document, options) {
    let report = null;
    const meshes = [];
    await document.transform(meshfix({ ...options, onReport: (r) => (report = r), onMesh: (m) => meshes.push(m) }));
    return { report, meshes };
}

async function roundTrip(document) {
    const { json, resources } = await io.writeJSON(document);
    const bytes = Buffer.from(JSON.stringify(json));
    const check = await validate(validator, bytes, 'test.gltf', null, (path) => resources[path]);
    const back = await io.readJSON({ json, resources });
    return { check, back };
}

const mesh = (document, name) => document.getRoot().listMeshes().find((m) => m.getName() === name);
const triangles = (document, name, p) => drawnTriangles(mesh(document, name).listPrimitives()[p]);

await test('transform: meshfix() is a glTF-Transform transform named "meshfix"', () => {
    const t = meshfix();
    return typeof t === 'function' && t.name === 'meshfix' ? [] : [`${typeof t} ${t.name}`];
});

const document = build();
const before = await roundTrip(document);
const { report, meshes } = await run(document);
const after = await roundTrip(document);

await test('transform: the input document is valid (0 errors, 0 warnings)', () =>
    before.check.numErrors === 0 && before.check.numWarnings === 0 ? [] : [JSON.stringify([...before.check.errors])]);

await test('transform: the cube\'s 5 reversed faces (10 triangles) and the sheet (by NORMAL) flip, 12 in all', () => {
    const problems = [];
    const cube = report.meshes.find((m) => m.name === 'cube'), sheet = report.meshes.find((m) => m.name === 'sheet');
    if (cube.trianglesFlipped !== 10 || cube.verdict !== 'repaired')
        problems.push(`cube: ${cube.summary}`);
    if (sheet.trianglesFlipped !== 2 || sheet.report.evidence.patchesByNormals !== 1)
        problems.push(`sheet: ${sheet.summary}`);
    for (const name of ['lid', 'good'])
        if (report.meshes.find((m) => m.name === name).trianglesFlipped !== 0)
            problems.push(`${name} changed`);
    const flips = report.primitives.filter((p) => p.mesh === 0).map((p) => p.trianglesFlipped).join();
    if (flips !== '2,2,0,2,2,2')
        problems.push(`cube primitives flipped ${flips}, expected 2,2,0,2,2,2`);
    if (report.trianglesFlipped !== 12 || report.meshesChanged !== 2 || report.primitivesChanged !== 6)
        problems.push(`totals: ${report.summary}`);
    return problems;
});

await test('transform: every form written as it should (8-bit kept, shared cloned, created, strip and fan as lists)', () => {
    const problems = [];
    const actions = report.primitives.filter((p) => p.mesh === 0).map((p) => p.action);
    const expected = ['indices rewritten', 'indices cloned and rewritten', 'unchanged', 'indices created',
        'TRIANGLE_STRIP rewritten as TRIANGLES', 'TRIANGLE_FAN rewritten as TRIANGLES'];
    if (actions.join() !== expected.join())
        problems.push(`actions: ${actions.join('; ')}`);
    if (report.accessorsCloned !== 1 || report.accessorsCreated !== 3 || report.accessorsRemoved !== 1 || report.primitivesConverted !== 2)
        problems.push(`counts: cloned ${report.accessorsCloned}, created ${report.accessorsCreated}, removed ${report.accessorsRemoved}, converted ${report.primitivesConverted}`);
    const back = after.back;
    const cube = mesh(back, 'cube').listPrimitives();
    const types = cube.map((p) => (p.getIndices() ? p.getIndices().getArray().constructor.name : 'none'));
    if (types.join() !== 'Uint8Array,Uint16Array,Uint32Array,Uint16Array,Uint16Array,Uint16Array')
        problems.push(`index types ${types}`);
    if (cube.map((p) => p.getMode()).join() !== '4,4,4,4,4,4')
        problems.push(`modes ${cube.map((p) => p.getMode())}`);
    // every cube triangle now faces out: the same as the quads' right triangles
    const outward = Object.values(FACES).map((q) => quadTriangles(q));
    const expectTriangles = [outward[0], outward[1], outward[2]];
    expectTriangles.forEach((t, p) => {
        if (triangles(back, 'cube', p).flat().join() !== t.join())
            problems.push(`cube primitive ${p}: ${triangles(back, 'cube', p).flat()}`);
    });
    // the lid keeps its own (shared) accessor, untouched
    if (triangles(back, 'lid', 0).flat().join() !== quadTriangles(FACES.zMax, true).join())
        problems.push(`lid changed: ${triangles(back, 'lid', 0).flat()}`);
    if (mesh(back, 'good').listPrimitives().map((p) => p.getMode()).join() !== '5,5,5,5,6,6')
        problems.push('the right cube\'s strips and fans were rewritten');
    return problems;
});

await test('transform: mirrored nodes and double-sided materials reported, never changed', () => {
    const problems = [];
    const mirrored = report.mirroredNodes.map((n) => n.name).join();
    if (mirrored !== 'mirror,mirrored child')
        problems.push(`mirrored nodes: ${mirrored}`);
    if (report.doubleSidedMaterials.length !== 1 || report.doubleSidedMaterials[0].primitivesFlipped !== 1)
        problems.push(`double-sided: ${JSON.stringify(report.doubleSidedMaterials)}`);
    const node = after.back.getRoot().listNodes().find((n) => n.getName() === 'mirror');
    if (node.getScale().join() !== '-1,1,1')
        problems.push('the mirrored node changed');
    if (!after.back.getRoot().listMaterials()[0].getDoubleSided())
        problems.push('the material changed');
    if (!/2 mirrored nodes, 1 double-sided material/.test(report.summary))
        problems.push(report.summary);
    return problems;
});

await test('transform: the output is valid under the Khronos glTF-Validator (0 errors, 0 warnings)', () =>
    after.check.numErrors === 0 && after.check.numWarnings === 0 ? [] : [`errors ${[...after.check.errors]}, warnings ${after.check.numWarnings}`]);

await test('transform: the same flips as the C library on the same mesh-space triangles', () => {
    if (!native)
        return ['no native build'];
    const results = runNative(native, meshes.map((m) => ({ indices: m.indices, positions: m.positions, normals: m.vertexNormals })), 'transform_native');
    return meshes.flatMap((m, i) => compareWithNative(m.result, results[i], m.mesh.getName()));
});

await test('transform: a second run flips nothing', async () => {
    const again = await run(after.back);
    return again.report.trianglesFlipped === 0 ? [] : [again.report.summary];
});

await test('transform: dryRun reports the same and writes nothing', async () => {
    const fresh = build();
    const json = JSON.stringify((await io.writeJSON(fresh)).json);
    const dry = await run(fresh, { dryRun: true });
    const problems = [];
    if (dry.report.trianglesFlipped !== 12 || !/^would fix 12 triangles/.test(dry.report.summary))
        problems.push(dry.report.summary);
    if (JSON.stringify((await io.writeJSON(fresh)).json) !== json)
        problems.push('the document changed');
    return problems;
});

await test('transform: normals: false leaves the open sheet as it is (no other evidence)', async () => {
    const { report: r } = await run(build(), { normals: false });
    const sheet = r.meshes.find((m) => m.name === 'sheet');
    return sheet.trianglesFlipped === 0 && r.trianglesFlipped === 10 ? [] : [r.summary];
});

await test('transform: policy "up" faces +y in glTF unless told otherwise', async () => {
    const { report: r } = await run(build(), { policy: 'up', normals: false });
    const sheet = r.meshes.find((m) => m.name === 'sheet');
    const { report: down } = await run(build(), { policy: 'up', up: '-y', normals: false });
    return sheet.trianglesFlipped === 2 && down.meshes.find((m) => m.name === 'sheet').trianglesFlipped === 0 ? [] : [r.summary, down.summary];
});

await test('transform: a primitive with an index out of range is skipped, its mesh still repaired', async () => {
    const doc = new Document();
    doc.setLogger(new Logger(Logger.Verbosity.ERROR));
    const buffer = doc.createBuffer();
    const corners = doc.createAccessor().setType('VEC3').setArray(new Float32Array(CORNERS)).setBuffer(buffer);
    const m = doc.createMesh('m');
    const faces = Object.values(FACES);
    const all = faces.flatMap((q, i) => quadTriangles(q, i === 0)); // face 0 reversed
    m.addPrimitive(doc.createPrimitive().setAttribute('POSITION', corners)
        .setIndices(doc.createAccessor().setType('SCALAR').setArray(new Uint16Array(all)).setBuffer(buffer)));
    m.addPrimitive(doc.createPrimitive().setAttribute('POSITION', corners)
        .setIndices(doc.createAccessor().setType('SCALAR').setArray(new Uint16Array([0, 1, 99])).setBuffer(buffer)));
    const { report: r } = await run(doc);
    const problems = [];
    if (r.skipped.length !== 1 || !/index 99 is out of range/.test(r.skipped[0].reason))
        problems.push(JSON.stringify(r.skipped));
    if (r.trianglesFlipped !== 2)
        problems.push(r.summary);
    return problems;
});

await test('transform: a document without meshes, and a mesh of points, are left alone', async () => {
    const empty = await run(new Document().setLogger(new Logger(Logger.Verbosity.ERROR)));
    const doc = new Document().setLogger(new Logger(Logger.Verbosity.ERROR));
    const points = doc.createAccessor().setType('VEC3').setArray(new Float32Array(CORNERS)).setBuffer(doc.createBuffer());
    doc.createMesh('points').addPrimitive(doc.createPrimitive().setAttribute('POSITION', points).setMode(0));
    const p = await run(doc);
    return empty.report.summary === 'clean: nothing to flip (0 triangles, 0 meshes)' && p.report.meshes[0].primitives === 0
        ? [] : [empty.report.summary, p.report.summary];
});

// The transform rejects with the library's invalid-argument text: followed
// by ": NAME " when JavaScript refused the option, alone when the library did.
async function transformRefuses(document, options, named) {
    const text = `meshfix: ${headerResults().find((r) => r.name === 'MESHFIX_ERROR_INVALID_ARGUMENT').text}`;
    try {
        await document.transform(meshfix(options));
    } catch (error) {
        const message = error instanceof MeshfixError && error.code === 'MESHFIX_ERROR_INVALID_ARGUMENT' &&
            (named === null ? error.message === text : error.message.startsWith(`${text}: ${named} `));
        return message ? [] : [`${named}: threw ${error.name} ${error.code}: ${error.message}`];
    }
    return [`${named}: the transform ran`];
}

await test('transform: its options are checked as orient\'s, before any mesh: unknown names, values no C field holds, its own', async () => {
    const empty = () => new Document().setLogger(new Logger(Logger.Verbosity.ERROR));
    const cases = [
        [{ polcy: 'seed' }, 'polcy'], [{ visibility: { rays: -1 } }, 'visibility.rays'], [{ visibility: { rays: 2 ** 40 } }, 'visibility.rays'],
        [{ visibility: { minSamples: NaN } }, 'visibility.minSamples'], [{ evidence: { sigmaa: 1 } }, 'evidence.sigmaa'],
        [{ dryRun: 'yes' }, 'dryRun'], [{ normals: 0 }, 'normals'], [{ onReport: 'log' }, 'onReport'],
        [{ positionsStride: 3 }, 'positionsStride'], [{ components: true }, 'components'], // one call's options, not the transform's
        [{ evidence: { vertexNormals: new Float32Array(3) } }, 'evidence.vertexNormals'], // each mesh's NORMAL is
        [{ policy: 'sdf' }, 'policy'],
    ];
    const problems = [];
    for (const [options, named] of cases) {
        problems.push(...await transformRefuses(build(), options, named));
        problems.push(...(await transformRefuses(empty(), options, named)).map((p) => `no meshes: ${p}`));
    }
    return problems;
});

await test('transform: an option the library refuses fails the transform (it would refuse every mesh), the document unchanged', async () => {
    const document = build();
    const json = JSON.stringify((await io.writeJSON(document)).json);
    const problems = [
        ...await transformRefuses(document, { visibility: { rays: 2 ** 24 + 1 } }, null),
        ...await transformRefuses(build(), { evidence: { sigma: -1 } }, null),
    ];
    if (JSON.stringify((await io.writeJSON(document)).json) !== json)
        problems.push('the document changed');
    return problems;
});

await test('transform: undefined options are as if left out', async () => {
    const { report: r } = await run(build(), { policy: undefined, dryRun: undefined, normals: undefined, visibility: { rays: undefined }, polcy: undefined });
    return r.trianglesFlipped === 12 ? [] : [r.summary];
});

await test('transform: policy "normals" refuses the meshes without NORMAL (NORMALS_REQUIRED), repairs the sheet by its NORMAL', async () => {
    const text = `meshfix: ${headerResults().find((r) => r.name === 'MESHFIX_ERROR_NORMALS_REQUIRED').text}`;
    const { report: r } = await run(build(), { policy: 'normals' });
    const problems = [];
    for (const name of ['cube', 'lid', 'good']) {
        const m = r.meshes.find((e) => e.name === name);
        if (m.error !== text)
            problems.push(`${name}: ${m.error || m.summary}`);
    }
    const sheet = r.meshes.find((m) => m.name === 'sheet');
    if (sheet.trianglesFlipped !== 2 || sheet.error !== undefined)
        problems.push(`sheet: ${sheet.error || sheet.summary}`);
    if (!/3 meshes refused/.test(r.summary))
        problems.push(r.summary);
    return problems;
});

// What a run prints, line by line: console's methods caught while the
// transform runs (glTF-Transform's Logger writes through console.info,
// .debug, .warn and .error).
async function printed(document, options) {
    const lines = [];
    const saved = {};
    for (const method of ['log', 'info', 'debug', 'warn', 'error']) {
        saved[method] = console[method];
        console[method] = (...args) => lines.push(...args.map(String).join(' ').split('\n'));
    }
    try {
        await document.transform(meshfix(options));
    } finally {
        Object.assign(console, saved);
    }
    return lines;
}

await test('transform: the summary is said once: the README\'s onReport printing it, the logger at info level (glTF-Transform\'s default)', async () => {
    let summary = null;
    const document = build().setLogger(new Logger(Logger.Verbosity.INFO));
    const lines = await printed(document, { onReport: (r) => { summary = r.summary; console.log(r.summary); } });
    const problems = [];
    const saying = lines.filter((l) => summary !== null && l.includes(summary));
    if (summary === null || !/mirrored node/.test(summary))
        problems.push(`summary: ${summary}`);
    if (saying.length !== 1)
        problems.push(`${saying.length} lines say the summary:`, ...lines);
    if (lines.length !== 1)
        problems.push(`${lines.length} lines printed, 1 expected:`, ...lines);
    return problems;
});

await test('transform: without onReport, the logger says the summary once at info level, and a line per mirrored node', async () => {
    const { report: r } = await run(build(), {});
    const lines = await printed(build().setLogger(new Logger(Logger.Verbosity.INFO)), {});
    const problems = [];
    if (lines.filter((l) => l === `meshfix: ${r.summary}`).length !== 1)
        problems.push(`the summary ${JSON.stringify(r.summary)} not said once:`, ...lines);
    const nodes = lines.filter((l) => /^meshfix: node ".*" mirrors its mesh/.test(l));
    if (r.mirroredNodes.length < 1 || nodes.length !== r.mirroredNodes.length)
        problems.push(`${nodes.length} mirrored-node lines, ${r.mirroredNodes.length} mirrored nodes`);
    if (lines.length !== 1 + r.mirroredNodes.length)
        problems.push(`${lines.length} lines:`, ...lines);
    const quiet = await printed(build().setLogger(new Logger(Logger.Verbosity.WARN)), {});
    if (quiet.length !== 0)
        problems.push('at warn level:', ...quiet);
    return problems;
});

console.log(`transform: ${failed()} failed`);
process.exit(failed() ? 1 : 0);
