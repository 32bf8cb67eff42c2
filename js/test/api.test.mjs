// The typed-array API: orient, inspect, check, weld, options and errors,
// the ES module and CommonJS entry points, and the WebAssembly against the
// native build of the same header on generated meshes.
//   node test/api.test.mjs NATIVE_BINARY
import { execFileSync } from 'node:child_process';
import { createRequire } from 'node:module';
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import util from 'node:util';
import * as esm from '../dist/meshfix.mjs';
import { bundleScope, compareWithNative, declaredFields, failed, headerResults, jsDir, random, runNative, test } from './common.mjs';

const { ready, orient, inspect, check, weld, MeshfixError, version } = esm;
const require = createRequire(import.meta.url);
const native = process.argv[2];

// a tetrahedron with its last face turned inside out (the README's example)
const tetraPositions = new Float32Array([0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1]);
const tetraIndices = () => new Uint32Array([0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 3, 2]);

// A UV sphere (or torus) with seams: positions repeat at the seam, as an engine's buffer does.
function sphere(rings, segments, torus) {
    const positions = [], indices = [];
    for (let r = 0; r <= rings; ++r)
        for (let s = 0; s <= segments; ++s) {
            const u = (s / segments) * 2 * Math.PI, v = (r / rings) * (torus ? 2 * Math.PI : Math.PI);
            if (torus)
                positions.push((2 + Math.cos(v)) * Math.cos(u), (2 + Math.cos(v)) * Math.sin(u), Math.sin(v));
            else
                positions.push(Math.sin(v) * Math.cos(u), Math.sin(v) * Math.sin(u), Math.cos(v));
        }
    const at = (r, s) => r * (segments + 1) + s;
    for (let r = 0; r < rings; ++r)
        for (let s = 0; s < segments; ++s) {
            const a = at(r, s), b = at(r + 1, s), c = at(r + 1, s + 1), d = at(r, s + 1);
            if (torus || r > 0)
                indices.push(a, b, c);
            if (torus || r < rings - 1)
                indices.push(a, c, d);
        }
    return { positions: new Float32Array(positions), indices: new Uint32Array(indices) };
}

function scramble(indices, share, seed) {
    const out = indices.slice();
    const next = random(seed);
    let reversed = 0;
    for (let t = 0; t < out.length / 3; ++t)
        if (next() < share) {
            [out[3 * t + 1], out[3 * t + 2]] = [out[3 * t + 2], out[3 * t + 1]];
            reversed++;
        }
    return { indices: out, reversed };
}

function throwsCode(body, code) {
    try {
        body();
    } catch (error) {
        return error instanceof MeshfixError && error.code === code ? [] : [`threw ${error.name} ${error.code}: ${error.message}`];
    }
    return [`did not throw ${code}`];
}

// The library's words for a result, read from meshfix.h (not from the WebAssembly).
const resultText = (name) => `meshfix: ${headerResults().find((r) => r.name === name).text}`;

// A MeshfixError of `code` whose message is the library's text: alone (the
// library refused), or followed by `: ${named} ` (JavaScript refused an
// option or argument before the call, naming it).
function refused(body, code, named) {
    const text = resultText(code);
    try {
        body();
    } catch (error) {
        if (!(error instanceof MeshfixError) || error.code !== code)
            return [`${named}: threw ${error.name} ${error.code}: ${error.message}`];
        if (named === null ? error.message !== text : !error.message.startsWith(`${text}: ${named} `))
            return [`${named}: message "${error.message}"`];
        return [];
    }
    return [`${named}: did not throw ${code}`];
}
const invalid = (body, named) => refused(body, 'MESHFIX_ERROR_INVALID_ARGUMENT', named);

function throwsType(body, Type, pattern) {
    try {
        body();
    } catch (error) {
        return error instanceof Type && pattern.test(error.message) ? [] : [`threw ${error.name}: ${error.message}`];
    }
    return [`did not throw ${Type.name}`];
}

await ready;

await test('ready resolves; version is the header\'s', () => {
    const header = readFileSync(join(jsDir, '..', 'meshfix.h'), 'utf8');
    const parts = ['MAJOR', 'MINOR', 'PATCH'].map((p) => header.match(new RegExp(`#define MESHFIX_VERSION_${p} (\\d+)`))[1]);
    return version === parts.join('.') ? [] : [`version ${version}, header ${parts.join('.')}`];
});

await test('orient: the README\'s tetrahedron, 1 triangle flipped, the same as in C', () => {
    const r = orient(tetraIndices(), tetraPositions);
    const problems = [];
    if (r.report.trianglesFlipped !== 1 || r.indices[10] !== 2 || r.indices[11] !== 3)
        problems.push(`flipped ${r.report.trianglesFlipped}, indices ${Array.from(r.indices)}`);
    if (r.summary !== 'fixed 1 triangle in 1 patch')
        problems.push(`summary "${r.summary}"`);
    if (r.report.verdict !== 'repaired' || Array.from(r.flipped).join() !== '0,0,0,1')
        problems.push(`verdict ${r.report.verdict}, flipped ${Array.from(r.flipped)}`);
    if (!(r.indices instanceof Uint32Array) || r.patchIds.length !== 4 || r.patchConfidence.length !== 1)
        problems.push('result arrays of the wrong type or length');
    // one closed patch alone: decided by its volume (MESHFIX_EVIDENCE_VOLUME)
    if (!(r.patchEvidence instanceof Uint8Array) || r.patchEvidence.length !== 1 || r.patchEvidence[0] !== 1)
        problems.push(`patchEvidence ${r.patchEvidence && Array.from(r.patchEvidence)}`);
    if (r.report.mesh.triangles !== 4 || r.report.mesh.componentsClosed !== 1 || !(r.report.mesh.signedVolume > 0))
        problems.push(`report.mesh ${JSON.stringify(r.report.mesh)}`);
    return problems;
});

await test('orient: the input is not changed, unless inPlace', () => {
    const input = tetraIndices();
    orient(input, tetraPositions);
    const problems = input[10] === 3 ? [] : ['input changed'];
    const r = orient(input, tetraPositions, { inPlace: true });
    if (r.indices !== input || input[10] !== 2)
        problems.push('inPlace did not write the input');
    return problems;
});

await test('orient: 16-bit, 8-bit and plain-array indices come back as given', () => {
    const problems = [];
    for (const [name, make] of [['Uint16Array', (a) => new Uint16Array(a)], ['Uint8Array', (a) => new Uint8Array(a)],
        ['Array', (a) => Array.from(a)]]) {
        const r = orient(make(tetraIndices()), tetraPositions);
        const type = name === 'Array' ? Uint32Array : { Uint16Array, Uint8Array }[name];
        if (!(r.indices instanceof type) || r.indices[10] !== 2 || r.report.trianglesFlipped !== 1)
            problems.push(`${name}: ${r.indices.constructor.name} ${Array.from(r.indices)}`);
    }
    return problems;
});

await test('orient: double positions, plain arrays and interleaved vertices (stride) give the same flips', () => {
    const problems = [];
    const interleaved = new Float32Array(4 * 8);
    for (let v = 0; v < 4; ++v)
        interleaved.set(tetraPositions.subarray(3 * v, 3 * v + 3), 8 * v);
    const variants = {
        Float64Array: orient(tetraIndices(), new Float64Array(tetraPositions)),
        Array: orient(tetraIndices(), Array.from(tetraPositions)),
        'stride 8': orient(tetraIndices(), interleaved, { positionsStride: 8 }),
        'no positions': orient(tetraIndices(), null),
    };
    for (const [name, r] of Object.entries(variants))
        if (Array.from(r.flipped).join() !== '0,0,0,1')
            problems.push(`${name}: flipped ${Array.from(r.flipped)}`);
    return problems;
});

await test('orient: a mesh already right comes back unchanged (clean, 0 flips)', () => {
    const fixed = orient(tetraIndices(), tetraPositions).indices;
    const again = orient(fixed, tetraPositions);
    return again.report.trianglesFlipped === 0 && again.report.verdict === 'clean' &&
        Array.from(again.indices).join() === Array.from(fixed).join() ? [] : [again.summary];
});

await test('orient: an empty mesh is clean', () => {
    const r = orient(new Uint32Array(0), new Float32Array(0));
    return r.report.verdict === 'clean' && r.indices.length === 0 ? [] : [r.summary];
});

await test('orient: policies by name; seed follows the lowest triangle, up faces +y', () => {
    const problems = [];
    const quad = new Float32Array([0, 0, 0, 1, 0, 0, 1, 0, 1, 0, 0, 1]); // in the y = 0 plane
    const down = new Uint32Array([0, 1, 2, 0, 2, 3]); // normal (1,0,0)x(1,0,1) = (0,-1,0)
    const firstReversed = new Uint32Array([0, 1, 2, 0, 1, 3, 0, 3, 2, 1, 2, 3]); // only triangle 0 faces in
    const seed = orient(firstReversed, tetraPositions, { policy: 'seed' });
    if (Array.from(seed.flipped).join() !== '0,1,1,1')
        problems.push(`seed flipped ${Array.from(seed.flipped)}, expected the other 3`);
    if (Array.from(orient(firstReversed, tetraPositions).flipped).join() !== '1,0,0,0')
        problems.push('auto did not flip triangle 0 alone');
    const up = orient(down, quad, { policy: 'up', up: 'y' });
    if (up.report.trianglesFlipped !== 2)
        problems.push(`up y flipped ${up.report.trianglesFlipped}`);
    const upVector = orient(down, quad, { policy: 'up', up: [0, -1, 0] });
    if (upVector.report.trianglesFlipped !== 0)
        problems.push(`up [0,-1,0] flipped ${upVector.report.trianglesFlipped}`);
    const auto = orient(down, quad);
    if (auto.report.trianglesFlipped !== 0)
        problems.push(`auto flipped a lone quad: ${auto.summary}`);
    for (const policy of ['majority', 'outward', 'visibility'])
        if (orient(tetraIndices(), tetraPositions, { policy }).report.trianglesFlipped !== 1)
            problems.push(`${policy} did not flip the one reversed face`);
    return problems;
});

await test('orient: NORMAL-like vertex and triangle normals as evidence turn an open quad', () => {
    const quad = new Float32Array([0, 0, 0, 1, 0, 0, 1, 0, 1, 0, 0, 1]);
    const down = new Uint32Array([0, 1, 2, 0, 2, 3]);
    const upNormals = new Float32Array([0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0]);
    const problems = [];
    const byVertex = orient(down, quad, { evidence: { vertexNormals: upNormals } });
    if (byVertex.report.trianglesFlipped !== 2 || byVertex.report.evidence.patchesByNormals !== 1)
        problems.push(`vertex normals: ${byVertex.summary}, ${JSON.stringify(byVertex.report.evidence)}`);
    const byTriangle = orient(down, quad, { policy: 'normals', evidence: { triangleNormals: [0, 1, 0, 0, 1, 0] } });
    if (byTriangle.report.trianglesFlipped !== 2)
        problems.push(`triangle normals: ${byTriangle.summary}`);
    problems.push(...invalid(() => orient(down, quad, { evidence: { vertexNormals: new Float32Array(6) } }), 'evidence.vertexNormals'));
    return problems;
});

await test('inspect: reports, writes nothing; components on request', () => {
    const input = tetraIndices();
    const r = inspect(input, tetraPositions, { components: true });
    const problems = [];
    if (r.report.verdict !== 'inconsistent' || r.report.mesh.edgesInconsistent !== 3 || input[10] !== 3)
        problems.push(`${r.summary} ${JSON.stringify(r.report.mesh)}`);
    if (!r.components || r.components.length !== 1 || r.components[0].closed !== true || r.components[0].triangles !== 4)
        problems.push(`components ${JSON.stringify(r.components)}`);
    if ('indices' in r || 'flipped' in r)
        problems.push('inspect returned indices');
    return problems;
});

await test('check: ok, or the requirement and the reason in words', () => {
    const problems = [];
    const bad = check(tetraIndices(), tetraPositions);
    if (bad.ok || bad.requirement !== 'consistent' || !/^not consistent: 3 edges/.test(bad.text) || bad.edge === null)
        problems.push(JSON.stringify(bad));
    const good = check(orient(tetraIndices(), tetraPositions).indices, tetraPositions, 'solid');
    if (!good.ok || good.requirement !== null || good.result !== 'MESHFIX_OK')
        problems.push(JSON.stringify(good));
    const open = check(new Uint32Array([0, 1, 2]), tetraPositions, ['consistent', 'closed']);
    if (open.ok || open.requirement !== 'closed' || !/^not closed/.test(open.text))
        problems.push(JSON.stringify(open));
    const invalid = check(new Uint32Array([0, 1, 7]), tetraPositions);
    if (invalid.ok || invalid.result !== 'MESHFIX_ERROR_INDEX_OUT_OF_RANGE' || !/^not valid input/.test(invalid.text))
        problems.push(JSON.stringify(invalid));
    const needs = check(tetraIndices(), null, 'outward');
    if (needs.ok || needs.result !== 'MESHFIX_ERROR_POSITIONS_REQUIRED')
        problems.push(JSON.stringify(needs));
    return problems;
});

await test('weld: remap to the lowest vertex within the tolerance', () => {
    const r = weld(new Float32Array([0, 0, 0, 1, 1, 1, 0, 0, 1e-7, 1, 1, 1]), 1e-5);
    return Array.from(r.remap).join() === '0,1,0,1' && r.uniqueCount === 2 ? [] : [JSON.stringify(r)];
});

await test('errors: the library\'s status as MeshfixError.code; bad options named', () => [
    ...throwsCode(() => orient([0, 1, 9], tetraPositions), 'MESHFIX_ERROR_INDEX_OUT_OF_RANGE'),
    ...throwsCode(() => orient([0, 1], tetraPositions), 'MESHFIX_ERROR_NOT_TRIANGLES'),
    ...throwsCode(() => orient(tetraIndices(), null, { policy: 'outward' }), 'MESHFIX_ERROR_POSITIONS_REQUIRED'),
    ...throwsCode(() => orient(tetraIndices(), tetraPositions, { evidence: { sigma: -1 } }), 'MESHFIX_ERROR_INVALID_ARGUMENT'),
    ...invalid(() => orient(tetraIndices(), tetraPositions, { policy: 'outwards' }), 'policy'),
    ...invalid(() => orient(tetraIndices(), tetraPositions, { policy: 'sdf' }), 'policy'),
    ...invalid(() => orient(tetraIndices(), tetraPositions, { topology: 'welded' }), 'topology'),
    ...throwsType(() => orient([0, -1, 2], tetraPositions), RangeError, /index -1/),
    ...invalid(() => orient(tetraIndices(), tetraPositions, { vertexCount: 5 }), 'vertexCount'),
    ...throwsType(() => orient('0 1 2', tetraPositions), TypeError, /indices must be/),
]);

await test('options: a value its C field cannot hold is refused, not defaulted: the library\'s invalid-argument text, naming it', () => {
    const cases = [
        // [path, options]: unsigned int, wasm32's size_t, float, and their kinds
        ...[2 ** 40, 2 ** 32, -1, 1e300, NaN, Infinity, 1.5, '5', null, true, 5n, [5]].map((rays) => ['visibility.rays', { visibility: { rays } }]),
        ['visibility.minSamples', { visibility: { minSamples: -5 } }],
        ['visibility.minSamples', { visibility: { minSamples: 2 ** 32 } }],
        ['seed', { seed: 2 ** 32 }], ['seed', { seed: -1 }], ['seed', { seed: 0.5 }],
        ['weldTolerance', { weldTolerance: 1e300 }], ['weldTolerance', { weldTolerance: NaN }],
        ['evidence.sigma', { evidence: { sigma: Infinity } }], ['visibility.kv', { visibility: { kv: '1.5' } }],
        ['up[1]', { up: [0, NaN, 0] }], ['up', { up: [0, 1] }], ['up', { up: 'w' }], ['up', { up: 'toString' }], ['up', { up: null }],
        ['visibility.flags', { visibility: { flags: 2 ** 32 } }], ['visibility.flags', { visibility: { flags: 'both' } }],
        ['policy', { policy: 5 }], ['policy', { policy: 'toString' }], ['policy', { policy: 'seed\0' }], ['topology', { topology: 1 }],
        ['positionsStride', { positionsStride: 1.5 }], ['positionsStride', { positionsStride: -3 }],
        ['vertexCount', { vertexCount: -1 }], ['components', { components: 1 }], ['inPlace', { inPlace: 'yes' }],
        ['evidence.vertexNormalsStride', { evidence: { vertexNormalsStride: 2 ** 31 } }],
        ['evidence.triangleNormals', { evidence: { triangleNormals: 'up' } }],
        ['evidence', { evidence: 5 }], ['visibility', { visibility: null }], ['evidence', { evidence: [1] }],
    ];
    const problems = [];
    for (const [path, options] of cases)
        problems.push(...invalid(() => orient(tetraIndices(), tetraPositions, options), path).map((p) => `${p} (${util.inspect(options, { breakLength: Infinity })})`));
    problems.push(...invalid(() => inspect(tetraIndices(), tetraPositions, { visibility: { rays: -1 } }), 'visibility.rays'));
    problems.push(...invalid(() => check(tetraIndices(), tetraPositions, 'consistent', { seed: NaN }), 'seed'));
    problems.push(...invalid(() => weld(tetraPositions, NaN), 'tolerance'));
    problems.push(...invalid(() => weld(tetraPositions, 1e300), 'tolerance'));
    problems.push(...invalid(() => weld(tetraPositions, 0, { vertexCount: 2 ** 33 }), 'vertexCount'));
    return problems;
});

await test('options: an unknown name is refused at every level, naming it (as the Python binding does)', () => [
    ...invalid(() => orient(tetraIndices(), tetraPositions, { polcy: 'seed' }), 'polcy'),
    ...invalid(() => orient(tetraIndices(), tetraPositions, { evidence: { sigmaa: 3 } }), 'evidence.sigmaa'),
    ...invalid(() => orient(tetraIndices(), tetraPositions, { visibility: { ray: 64 } }), 'visibility.ray'),
    ...invalid(() => orient(tetraIndices(), tetraPositions, { sdf: { step: 1 } }), 'sdf'), // C callbacks: not offered
    ...invalid(() => orient(tetraIndices(), tetraPositions, { memory: {} }), 'memory'),
    ...invalid(() => orient(tetraIndices(), tetraPositions, { indexSize: 2 }), 'indexSize'), // set from the arrays
    ...invalid(() => orient(tetraIndices(), tetraPositions, { 'evidence.sigma': 3 }), 'evidence.sigma'),
    ...invalid(() => orient(tetraIndices(), tetraPositions, { up: 'y', evidence: { sigma: 3, vertexNormals: null, extra: 1 } }), 'evidence.extra'),
    ...invalid(() => inspect(tetraIndices(), tetraPositions, { component: true }), 'component'),
    ...invalid(() => check(tetraIndices(), tetraPositions, 'closed', { polcy: 'seed' }), 'polcy'),
    ...invalid(() => weld(tetraPositions, 0, { policy: 'seed' }), 'policy'), // weld takes positionsStride and vertexCount
]);

await test('options: values the C field holds reach the library, which refuses some in its own words', () => {
    const quadNormals = new Float32Array(12);
    const problems = [
        ...invalid(() => orient(tetraIndices(), tetraPositions, { visibility: { rays: 2 ** 24 + 1 } }), null),
        ...invalid(() => orient(tetraIndices(), tetraPositions, { visibility: { rays: 2 ** 32 - 1 } }), null), // wasm32's size_t holds it
        ...invalid(() => orient(tetraIndices(), tetraPositions, { visibility: { minSamples: 65537 } }), null),
        ...invalid(() => orient(tetraIndices(), tetraPositions, { evidence: { sigma: -1 } }), null),
        ...invalid(() => orient(tetraIndices(), tetraPositions, { evidence: { minConfidence: 2 } }), null),
        ...invalid(() => orient(tetraIndices(), tetraPositions, { visibility: { eps: 2 } }), null),
        ...invalid(() => orient(tetraIndices(), tetraPositions, { evidence: { vertexNormals: quadNormals, vertexNormalsStride: 2 } }), null),
        ...invalid(() => orient(tetraIndices(), tetraPositions, { positionsStride: 2 }), null),
    ];
    const most = orient(tetraIndices(), tetraPositions, { policy: 'visibility', visibility: { rays: 2 ** 24 } });
    if (most.report.evidence.raysCast !== 2 ** 24)
        problems.push(`rays 2^24: ${most.report.evidence.raysCast} rays cast`);
    if (orient(tetraIndices(), tetraPositions, { policy: 'visibility', seed: 2 ** 32 - 1 }).report.trianglesFlipped !== 1)
        problems.push('seed 2^32-1');
    const samples = orient(tetraIndices(), tetraPositions, { policy: 'visibility', visibility: { rays: 8, minSamples: 65536 } });
    if (samples.report.trianglesFlipped !== 1)
        problems.push(`minSamples 65536: ${samples.summary}`);
    return problems;
});

await test('options: undefined is as if left out (any name, any level); null options too, and null normals', () => {
    const plain = orient(tetraIndices(), tetraPositions, { policy: 'visibility' });
    const same = (r) => JSON.stringify([r.report, Array.from(r.flipped)]) === JSON.stringify([plain.report, Array.from(plain.flipped)]);
    const problems = [];
    const variants = {
        undefined: { policy: 'visibility', topology: undefined, up: undefined, seed: undefined, evidence: undefined, components: undefined,
            visibility: { rays: undefined, minSamples: undefined, flags: undefined }, polcy: undefined, positionsStride: undefined },
        'null normals': { policy: 'visibility', evidence: { vertexNormals: null, triangleNormals: null } },
    };
    for (const [name, options] of Object.entries(variants))
        if (!same(orient(tetraIndices(), tetraPositions, options)))
            problems.push(`${name}: not the default`);
    if (orient(tetraIndices(), tetraPositions, null).report.trianglesFlipped !== 1 || orient(tetraIndices(), tetraPositions, undefined).report.trianglesFlipped !== 1)
        problems.push('null or undefined options');
    if (weld(tetraPositions, undefined, { vertexCount: undefined }).uniqueCount !== 4)
        problems.push('weld with undefined tolerance');
    return problems;
});

await test('policy "normals" without positions or without normals: the library\'s POSITIONS_REQUIRED and NORMALS_REQUIRED, in its words', () => {
    const normals = new Float32Array(12);
    return [
        ...refused(() => orient(tetraIndices(), null, { policy: 'normals' }), 'MESHFIX_ERROR_POSITIONS_REQUIRED', null),
        ...refused(() => orient(tetraIndices(), null, { policy: 'normals', evidence: { vertexNormals: normals } }), 'MESHFIX_ERROR_POSITIONS_REQUIRED', null),
        ...refused(() => orient(tetraIndices(), tetraPositions, { policy: 'normals' }), 'MESHFIX_ERROR_NORMALS_REQUIRED', null),
        ...refused(() => orient(tetraIndices(), tetraPositions, { policy: 'normals', evidence: { vertexNormals: null } }), 'MESHFIX_ERROR_NORMALS_REQUIRED', null),
    ];
});

// What the bundle does not export: its load-time check of the struct table, and what it made of the WebAssembly.
const bundle = bundleScope(['parseLayout', 'layoutProblems', 'layoutText', 'load', 'USES']);
await bundle.ready;
const { scope } = bundle;
const table = scope.layoutText(scope.wasm.e);
const layoutProblems = (edit) => scope.layoutProblems(scope.parseLayout(edit(table)), scope.USES);
const moved = (line, by) => (t) => t.replace(new RegExp(`^(${line}) (\\d+)`, 'm'), (_, head, offset) => `${head} ${+offset + by}`);
const dropped = (line) => (t) => t.replace(new RegExp(`^${line} .*\n`, 'm'), '');

await test('layout: the WebAssembly\'s table of meshfix.h\'s structs passes the load-time check', () => {
    const problems = layoutProblems((t) => t);
    for (const name of ['meshfix_options', 'meshfix_outputs', 'meshfix_report', 'meshfix_component', 'meshfix_check_failure'])
        if (!(name in scope.wasm.layout.structs))
            problems.push(`no ${name} in the table`);
    return problems;
});

await test('layout: the check catches a wrong offset, a field left out (middle or end), a kind or a field this file uses', () => {
    const cases = [
        ['visibility.min_samples 4 bytes later', moved('meshfix_options visibility\\.min_samples', 4), /meshfix_options\.visibility\.min_samples is at byte 68, where C would put it .* is 64/],
        ['seed 4 bytes earlier', moved('meshfix_options seed', -4), /meshfix_options\.seed is at byte 28/],
        ['mesh.edges_boundary not listed', dropped('meshfix_report mesh\\.edges_boundary'), /meshfix_report\.mesh\.edges_manifold is at byte/],
        ['signed_volume (the last field) not listed', dropped('meshfix_component signed_volume'), /meshfix_component is 56 bytes, its listed fields take 48/],
        ['policy a float', (t) => t.replace(/^(meshfix_options policy \d+ 4 4) u/m, '$1 f'), /meshfix_options\.policy is f32, taken here as integer/],
        ['components_capacity not listed', dropped('meshfix_outputs components_capacity'), /meshfix_outputs\.components_capacity is missing/],
        ['a pointer of 2 bytes', (t) => t.replace(/^(meshfix_outputs flipped \d+) 4 4 p/m, '$1 2 2 p'), /meshfix_outputs\.flipped is 2 bytes of kind p/],
        ['a struct of no size', dropped('meshfix_report -'), /meshfix_report has fields but no size/],
    ];
    const problems = [];
    for (const [name, edit, expected] of cases) {
        if (edit(table) === table)
            problems.push(`${name}: the edit changed nothing`);
        const found = layoutProblems(edit);
        if (!found.some((p) => expected.test(p)))
            problems.push(`${name}: ${found.length ? found.join('; ') : 'no problem found'}`);
    }
    return problems;
});

await test('layout: a table that fails the check fails the load, loudly', () => {
    const e = scope.wasm.e;
    const bad = moved('meshfix_report verdict', 8)(table);
    const fake = { ...e, mfjs_layout(buffer, size) { // the real exports, the table edited
        const bytes = new TextEncoder().encode(`${bad}\0`);
        if (buffer !== 0)
            new Uint8Array(e.memory.buffer, buffer, size).set(bytes.subarray(0, size));
        return bytes.length - 1;
    } };
    try {
        scope.load(fake);
    } catch (error) {
        return /WebAssembly's structs are not what this JavaScript reads and writes.*meshfix_report\.verdict is at byte 8/.test(error.message) ? [] : [error.message];
    }
    return ['load() took the edited table'];
});

await test('result codes: the JavaScript side has every one of meshfix.h\'s MESHFIX_RESULT_LIST, by value', () => {
    const header = headerResults().map((r) => r.name);
    const problems = scope.wasm.results.join() === header.join() ? [] : [`WebAssembly ${scope.wasm.results}, header ${header}`];
    if (!header.includes('MESHFIX_ERROR_NORMALS_REQUIRED'))
        problems.push('the header has no MESHFIX_ERROR_NORMALS_REQUIRED (read wrongly?)');
    return problems;
});

await test('policies and verdicts: the library\'s names (meshfix_policy_string, meshfix_verdict_string), each policy taken but those that call C; the types and the README list them', () => {
    const problems = [];
    const names = scope.wasm.policies.filter((_, i) => !scope.wasm.callsC[i]);
    if (scope.wasm.policies.length < 8 || scope.wasm.policies.filter((_, i) => scope.wasm.callsC[i]).join() !== 'sdf')
        problems.push(`policies ${scope.wasm.policies}, calling C ${scope.wasm.callsC}`);
    try {
        orient(tetraIndices(), tetraPositions, { policy: 'sdf' });
        problems.push('policy sdf was taken');
    } catch (error) {
        if (!/calls a C function/.test(error.message))
            problems.push(`sdf: ${error.message}`);
    }
    for (const policy of names)
        try {
            orient(tetraIndices(), tetraPositions, { policy, evidence: { triangleNormals: new Float32Array(12) } });
        } catch (error) {
            problems.push(`${policy}: ${error.message}`);
        }
    const types = readFileSync(join(jsDir, 'meshfix.d.ts'), 'utf8').match(/^export type Policy = (.*);$/m)[1];
    const declared = [...types.matchAll(/'([^']+)'/g)].map((m) => m[1]);
    if (declared.join() !== names.join())
        problems.push(`meshfix.d.ts Policy: ${declared}; the library: ${names}`);
    const verdicts = readFileSync(join(jsDir, 'meshfix.d.ts'), 'utf8').match(/^export type Verdict = (.*);$/m)[1];
    const verdictsDeclared = [...verdicts.matchAll(/'([^']+)'/g)].map((m) => m[1]);
    if (verdictsDeclared.join() !== scope.wasm.verdicts.join())
        problems.push(`meshfix.d.ts Verdict: ${verdictsDeclared}; the library: ${scope.wasm.verdicts}`);
    const readme = readFileSync(join(jsDir, 'README.md'), 'utf8').match(/^\| `policy` \| ([^|]*) \|/m)[1];
    const listed = [...readme.matchAll(/`'([^']+)'`/g)].map((m) => m[1]);
    if (listed.join() !== names.join())
        problems.push(`README policy row: ${listed}; the library: ${names}`);
    return problems;
});

await test('meshfix.d.ts declares the options the calls take and the report and components they return', () => {
    const problems = [];
    const compare = (what, declared, actual) => {
        const missing = actual.filter((n) => !declared.includes(n)), extra = declared.filter((n) => !actual.includes(n));
        if (missing.length || extra.length)
            problems.push(`${what}: not declared ${missing}; declared, not there ${extra}`);
    };
    compare('Options', declaredFields('Options'), [...scope.wasm.schemas.call.keys()]);
    const r = inspect(tetraIndices(), tetraPositions, { components: true });
    const report = declaredFields('Report').filter((n) => n !== 'mesh' && n !== 'evidence')
        .concat(declaredFields('MeshFacts').map((n) => `mesh.${n}`), declaredFields('EvidenceCounts').map((n) => `evidence.${n}`));
    const flat = (o, prefix = '') => Object.entries(o).flatMap(([k, v]) => (v !== null && typeof v === 'object' ? flat(v, `${prefix}${k}.`) : [`${prefix}${k}`]));
    compare('Report', report, flat(r.report));
    compare('Component', declaredFields('Component'), Object.keys(r.components[0]));
    return problems;
});

await test('memory: 300 calls and a 200k-triangle mesh leave the WebAssembly heap where it was', () => {
    const big = sphere(250, 400, false);
    for (let i = 0; i < 300; ++i)
        orient(tetraIndices(), tetraPositions);
    const r = orient(scramble(big.indices, 0.5, 7).indices, big.positions);
    const mark = orient(tetraIndices(), tetraPositions); // still works after the heap grew
    return r.report.mesh.triangles === big.indices.length / 3 && mark.report.trianglesFlipped === 1 ? [] : [r.summary];
});

await test('CommonJS entry: require() gives the same API and the same answers', async () => {
    const cjs = require('../dist/meshfix.cjs');
    await cjs.ready;
    const problems = [];
    const names = Object.keys(esm).sort().join();
    if (Object.keys(cjs).sort().join() !== names)
        problems.push(`CommonJS exports ${Object.keys(cjs).sort()} vs ES module ${names}`);
    const r = cjs.orient(tetraIndices(), tetraPositions);
    if (r.summary !== 'fixed 1 triangle in 1 patch')
        problems.push(r.summary);
    return problems;
});

await test('meshfix.d.ts declares exactly what the modules export', () => {
    const declared = new Set();
    for (const m of readFileSync(join(jsDir, 'meshfix.d.ts'), 'utf8').matchAll(/^export (?:const|function|class) (\w+)/gm))
        declared.add(m[1]);
    const exported = Object.keys(esm);
    const missing = exported.filter((n) => !declared.has(n)), extra = [...declared].filter((n) => !exported.includes(n));
    return missing.length || extra.length ? [`not declared: ${missing}; declared, not exported: ${extra}`] : [];
});

await test('a call before `ready` throws a clear error (fresh process)', () => {
    const out = execFileSync(process.execPath, ['-e',
        `const m = require(${JSON.stringify(join(jsDir, 'dist/meshfix.cjs'))});
         try { m.orient([0, 1, 2], [0, 0, 0, 1, 0, 0, 0, 1, 0]); console.log('no error'); }
         catch (e) { console.log(e.message); }`]).toString();
    return /not ready yet; `await ready`/.test(out) ? [] : [out];
});

// The same meshes through the WebAssembly and the native build.
if (native) {
    const meshes = [];
    const shapes = { sphere: sphere(40, 64, false), torus: sphere(48, 96, true), 'sphere 200k': sphere(250, 400, false) };
    let seed = 1;
    for (const [name, shape] of Object.entries(shapes))
        for (const share of [0.1, 0.5, 0.9])
            for (const normals of [false, true]) {
                const { indices } = scramble(shape.indices, share, seed++);
                // vertex normals: outward for the sphere, the torus's own
                let vertexNormals = null;
                if (normals) {
                    vertexNormals = new Float32Array(shape.positions.length);
                    for (let v = 0; v < shape.positions.length / 3; ++v) {
                        const [x, y, z] = shape.positions.subarray(3 * v, 3 * v + 3);
                        if (name === 'torus') {
                            const k = 2 / Math.hypot(x, y);
                            vertexNormals.set([x - k * x, y - k * y, z], 3 * v);
                        } else {
                            vertexNormals.set([x, y, z], 3 * v);
                        }
                    }
                }
                for (const policy of ['auto', 'majority', 'seed'])
                    meshes.push({ label: `${name}, ${share * 100}% reversed, ${normals ? 'normals, ' : ''}${policy}`,
                        indices, positions: shape.positions, normals: vertexNormals, policy });
            }
    const results = runNative(native, meshes, 'api_native');
    let flips = 0, triangles = 0;
    await test(`WebAssembly and native meshfix.h agree on ${meshes.length} generated meshes (flips, report, summary)`, () => {
        const problems = [];
        meshes.forEach((m, i) => {
            const options = { policy: m.policy };
            if (m.normals)
                options.evidence = { vertexNormals: m.normals };
            const r = orient(m.indices, m.positions, options);
            problems.push(...compareWithNative(r, results[i], m.label));
            flips += r.report.trianglesFlipped;
            triangles += r.flipped.length;
        });
        return problems;
    });
    console.log(`    (${triangles} triangles compared one by one, ${flips} of them flipped)`);
}

console.log(`api: ${failed()} failed`);
process.exit(failed() ? 1 : 0);
