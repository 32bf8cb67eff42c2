// The page's readers and writers (page/mesh_files.js, page/gltf_file.js),
// under node from the built page:
//   node test/page_files.test.mjs PAGE_DIR MESHFIX_CLI [ASSIMP_MODELS]
// Small hand-written files read as they should; real files of
// assimp-testmodels, scrambled (tests/cli/meshcheck.js), repaired to the
// same bytes as the command-line tool writes.
import { execFileSync } from 'node:child_process';
import { existsSync, mkdirSync, readdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { join, resolve } from 'node:path';
import { pathToFileURL } from 'node:url';
import { buildDir, failed, jsDir, skip, test } from './common.mjs';

const [pageDir, cli, models] = process.argv.slice(2);
const page = (f) => import(pathToFileURL(join(resolve(pageDir), f)).href);
const { readMeshFile, repairMeshFile } = await page('mesh_files.js');
const { repairGltf } = await page('gltf_file.js');
const meshcheck = join(jsDir, '..', 'tests', 'cli', 'meshcheck.js');
const out = join(buildDir, 'page-files');
rmSync(out, { recursive: true, force: true });
mkdirSync(out, { recursive: true });
const bytes = (text) => new TextEncoder().encode(text);
const same = (a, b) => a.length === b.length && a.every((x, i) => x === b[i]);
const expect = (problems, what, got, want) => {
    if (JSON.stringify(got) !== JSON.stringify(want))
        problems.push(`${what}: ${JSON.stringify(got)}, expected ${JSON.stringify(want)}`);
};

// a unit cube as 12 triangles, counter-clockwise from outside
const CUBE_V = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]];
const CUBE_F = [[0, 2, 1], [0, 3, 2], [4, 5, 6], [4, 6, 7], [0, 1, 5], [0, 5, 4], [1, 2, 6], [1, 6, 5], [2, 3, 7], [2, 7, 6],
    [3, 0, 4], [3, 4, 7]];

await test('OBJ: CRLF, comments, negative indices, v/vt/vn, a quad as two triangles, a vertex per (v, vn)', () => {
    const text = '# a quad and a triangle\r\nv 0 0 0\r\nv 1 0 0\r\nv 1 1 0\r\nv 0 1 0\r\nvn 0 0 1\r\nvt 0 0\r\n' +
        'f 1/1/1 2/1/1 3/1/1 4/1/1 # quad\r\nf -4 -2 -1\r\n';
    const f = readMeshFile('a.obj', bytes(text));
    const problems = [];
    expect(problems, 'faces', f.unit.faceCount, 2);
    expect(problems, 'indices', f.unit.indices, [0, 1, 2, 0, 2, 3, 4, 5, 6]);
    expect(problems, 'triangle faces', f.unit.triangleFace, [0, 0, 1]);
    expect(problems, 'vertex normals', f.unit.vertexNormals, [0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0]);
    const written = new TextDecoder().decode(f.write(Uint8Array.of(1, 1)));
    expect(problems, 'written', written, text.replace('f 1/1/1 2/1/1 3/1/1 4/1/1', 'f 1/1/1 4/1/1 3/1/1 2/1/1')
        .replace('f -4 -2 -1', 'f -4 -1 -2'));
    return problems;
});

await test('OBJ: an index out of range is refused with its text', () => {
    try {
        readMeshFile('bad.obj', bytes('v 0 0 0\nf 1 2 3\n'));
        return ['not refused'];
    } catch (error) {
        return /index '2' out of range/.test(error.message) ? [] : [error.message];
    }
});

// A facet whose corners were turned with its normal as exported is
// repaired (corners turned back, the normal kept); one whose normal was
// computed again from its turned corners agrees with them, and the
// library keeps what the file's normals and winding both say.
await test('STL ASCII: a cube with one facet\'s corners turned is repaired; turned with its normal, it is kept', async () => {
    const facet = (f, turn, normalToo = false) => {
        const [a, b, c] = turn ? [f[0], f[2], f[1]] : f;
        const p = CUBE_V;
        const [na, nb, nc] = normalToo ? [a, b, c] : f;
        const u = [0, 1, 2].map((k) => p[nb][k] - p[na][k]), w = [0, 1, 2].map((k) => p[nc][k] - p[na][k]);
        const n = [u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]];
        return ` facet normal ${n.join(' ')}\n  outer loop\n` + [a, b, c].map((v) => `   vertex ${p[v].join(' ')}\n`).join('') +
            '  endloop\n endfacet\n';
    };
    const good = `solid cube\n${CUBE_F.map((f) => facet(f, false)).join('')}endsolid cube\n`;
    const bad = `solid cube\n${CUBE_F.map((f, i) => facet(f, i === 4)).join('')}endsolid cube\n`;
    const r = await repairMeshFile('cube.stl', bytes(bad));
    const problems = [];
    expect(problems, 'flips', r.flips, 1);
    expect(problems, 'vertices (welded)', r.parts[0].positions.length / 3, 8);
    if (!same(r.output, bytes(good)))
        problems.push(`written:\n${new TextDecoder().decode(r.output).split('\n').slice(28, 36).join('\n')}`);
    const both = `solid cube\n${CUBE_F.map((f, i) => facet(f, i === 4, true)).join('')}endsolid cube\n`;
    const kept = await repairMeshFile('cube.stl', bytes(both));
    expect(problems, 'flips (turned with its normal)', kept.flips, 0);
    return problems;
});

await test('PLY: ascii, binary little- and big-endian give the same triangles', async () => {
    const header = (format) => `ply\nformat ${format} 1.0\ncomment cube\nelement vertex 8\nproperty float x\n` +
        'property float y\nproperty float z\nelement face 12\nproperty list uchar int vertex_indices\nend_header\n';
    const ascii = header('ascii') + CUBE_V.map((v) => `${v.join(' ')}\n`).join('') +
        CUBE_F.map((f) => `3 ${f.join(' ')}\n`).join('');
    const binary = (little) => {
        const h = bytes(header(little ? 'binary_little_endian' : 'binary_big_endian'));
        const data = new DataView(new ArrayBuffer(8 * 12 + 12 * 13));
        let at = 0;
        for (const v of CUBE_V)
            for (const x of v) {
                data.setFloat32(at, x, little);
                at += 4;
            }
        for (const f of CUBE_F) {
            data.setUint8(at++, 3);
            for (const i of f) {
                data.setInt32(at, i, little);
                at += 4;
            }
        }
        const all = new Uint8Array(h.length + data.byteLength);
        all.set(h);
        all.set(new Uint8Array(data.buffer), h.length);
        return all;
    };
    const problems = [];
    for (const [name, file] of [['ascii', bytes(ascii)], ['little', binary(true)], ['big', binary(false)]]) {
        const f = readMeshFile('cube.ply', file);
        expect(problems, `${name}: indices`, f.unit.indices, CUBE_F.flat());
        expect(problems, `${name}: positions`, f.unit.positions, CUBE_V.flat());
        // a turned face written back: corners 2 and 3 swapped in place
        const turned = readMeshFile('cube.ply', f.write(Uint8Array.from(CUBE_F, (_, i) => i === 3)));
        const want = CUBE_F.map((t, i) => (i === 3 ? [t[0], t[2], t[1]] : t)).flat();
        expect(problems, `${name}: written and read again`, turned.unit.indices, want);
    }
    return problems;
});

await test('glTF: a .glb that is not one is refused with a message', async () => {
    try {
        await repairGltf('x.glb', bytes('not a glb'));
        return ['not refused'];
    } catch (error) {
        return error.message ? [] : ['no message'];
    }
});

await test('render: a face seen from its front is grey, from behind blue (drawn, not culled), flipped red and, when small, ringed; a mirror swaps sides', async () => {
    const { render, frame, pixelKind } = await page('render.js');
    const canvas = { width: 64, height: 48, pixels: null };
    canvas.getContext = () => ({
        createImageData: (w, h) => ({ data: new Uint8ClampedArray(4 * w * h) }),
        putImageData: (image) => (canvas.pixels = image.data),
    });
    // one triangle in the plane z = 0, counter-clockwise seen from +z, and its view from +z and -z
    const part = { positions: Float32Array.of(0, 0, 0, 1, 0, 0, 0, 1, 0), indices: Uint32Array.of(0, 1, 2), flipped: Uint8Array.of(1) };
    const kinds = (parts, pitch, showFlipped) => {
        const counts = render(canvas, parts, { ...frame(parts, 1), yaw: 0, pitch }, { showFlipped });
        let grey = 0;
        for (let i = 0; i < canvas.pixels.length; i += 4)
            grey += pixelKind(canvas.pixels[i], canvas.pixels[i + 1], canvas.pixels[i + 2]) === 'other' &&
                canvas.pixels[i] < 250;
        return { red: counts.red, faceRed: counts.faceRed, rings: counts.rings, blue: counts.blue, grey, drawn: counts.drawn };
    };
    // with y up, yaw 0 and pitch 0 put the eye on +z: the triangle faces it, the reversed one turns its back
    const front = kinds([part], 0, false), back = kinds([{ ...part, indices: Uint32Array.of(0, 2, 1) }], 0, false);
    const red = kinds([part], 0, true), mirrored = kinds([{ ...part, mirrored: true }], 0, false);
    const problems = [];
    if (!(front.drawn > 100 && front.grey === front.drawn && front.blue === 0))
        problems.push(`front: ${JSON.stringify(front)}`);
    if (!(back.drawn === front.drawn && back.blue === back.drawn))
        problems.push(`back: ${JSON.stringify(back)}`);
    if (!(red.faceRed === front.drawn && red.red === red.faceRed && red.rings === 0))
        problems.push(`flipped: ${JSON.stringify(red)}`);
    // drawn small (under 400 pixels), a flipped face is ringed as well
    Object.assign(canvas, { width: 24, height: 18 });
    const small = kinds([part], 0, true);
    if (!(small.faceRed === small.drawn && small.drawn > 0 && small.rings === 1 && small.red > small.faceRed))
        problems.push(`small and flipped: ${JSON.stringify(small)}`);
    if (!(mirrored.blue === front.drawn))
        problems.push(`mirrored: ${JSON.stringify(mirrored)}`);
    return problems;
});

// ---- real files against the command-line tool ----
if (!models || !existsSync(join(models, 'STL', 'Spider_binary.stl'))) {
    skip('the page and the CLI on assimp-testmodels', `${models} is missing (apt-get install assimp-testmodels)`);
} else {
    const files = ['STL/Spider_binary.stl', 'STL/Spider_ascii.stl', 'STL/sphereWithHole.stl', 'PLY/cube.ply',
        'PLY/cube_binary.ply', 'PLY/Wuson.ply', 'OBJ/spider.obj', 'OBJ/box.obj', 'OBJ/WusonOBJ.obj', 'OFF/../PLY/big-endian',
        'glTF2/BoxTextured-glTF-Binary/BoxTextured.glb', 'glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb'];
    for (const f of files) {
        let input = join(models, f);
        if (f.endsWith('big-endian')) {
            input = join(out, 'cube_big_endian.ply');
            execFileSync('node', [meshcheck, 'big-endian', join(models, 'PLY/cube_binary.ply'), input]);
        }
        const name = input.split('/').pop();
        await test(`scrambled ${name}: the page writes the CLI's bytes`, async () => {
            const scrambled = join(out, name), fixed = join(out, `cli_${name}`);
            execFileSync('node', [meshcheck, 'scramble', input, scrambled, '11', '0.3']);
            execFileSync(cli, ['--quiet', scrambled, fixed]);
            const data = new Uint8Array(readFileSync(scrambled));
            const r = /\.glb$/.test(name) ? await repairGltf(name, data) : await repairMeshFile(name, data);
            writeFileSync(join(out, `page_${name}`), r.output);
            const problems = [];
            if (r.flips === 0)
                problems.push('nothing flipped');
            if (!r.byteExact)
                problems.push('not written in place');
            if (!same(r.output, readFileSync(fixed)))
                problems.push(`${name}: the page's output differs from the CLI's (${join(out, `page_${name}`)}, ${fixed})`);
            return problems;
        });
    }
    await test('a scrambled .gltf with its .bin and image dropped beside it: repaired, written by glTF-Transform as a .glb ' +
        'with the flips the CLI makes', async () => {
        const dir = join(out, 'gltf');
        mkdirSync(dir, { recursive: true });
        mkdirSync(join(out, 'cli_gltf'), { recursive: true });
        const scrambled = join(dir, 'BoxTextured.gltf');
        execFileSync('node', [meshcheck, 'scramble', join(models, 'glTF2/BoxTextured-glTF/BoxTextured.gltf'), scrambled, '11', '0.5']);
        const json = JSON.parse(execFileSync(cli, ['--json', scrambled, join(out, 'cli_gltf', 'BoxTextured.gltf')],
            { encoding: 'utf8' }));
        const flips = json.files[0].meshes.reduce((n, m) => n + m.flipped.faces, 0);
        const resources = new Map();
        for (const f of readdirSync(dir))
            if (f !== 'BoxTextured.gltf')
                resources.set(f, new Uint8Array(readFileSync(join(dir, f))));
        const r = await repairGltf('BoxTextured.gltf', new Uint8Array(readFileSync(scrambled)), resources);
        const problems = [];
        expect(problems, 'flips', r.flips, flips);
        expect(problems, 'written in place', r.byteExact, false);
        expect(problems, 'name', r.outputName, 'BoxTextured.fixed.glb');
        const again = await repairGltf(r.outputName, r.output);
        expect(problems, 'flips in the output', again.flips, 0);
        if (flips === 0)
            problems.push('the CLI flipped nothing');
        return problems;
    });
}
process.exit(failed() ? 1 : 0);
