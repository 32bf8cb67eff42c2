// Helpers shared by the JavaScript tests: result lines, a seeded random
// stream, glTF triangles as the spec draws them (written apart from
// src/gltf.js, so that a mistake there is not copied here), the native
// reference build and the Khronos validator.
import { execFileSync } from 'node:child_process';
import { readFileSync, writeFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

export const here = dirname(fileURLToPath(import.meta.url));
export const jsDir = join(here, '..');
export const buildDir = join(jsDir, 'build');

let failures = 0;

// `ok   name` or `FAIL name` (with the details indented), as tests/run_all.sh prints.
export function report(name, passed, details) {
    if (passed) {
        console.log(`ok   ${name}`);
    } else {
        failures++;
        console.log(`FAIL ${name}`);
        for (const line of String(details || '').split('\n').filter(Boolean).slice(0, 20))
            console.log(`    ${line}`);
    }
    return passed;
}

export function skip(name, reason) {
    console.log(`SKIP ${name}: ${reason}`);
}

export async function test(name, body) {
    try {
        const problems = (await body()) || [];
        return report(name, problems.length === 0, problems.join('\n'));
    } catch (error) {
        return report(name, false, error && error.stack ? error.stack : String(error));
    }
}

export function failed() {
    return failures;
}

// The bundle's own scope, for tests of what it does not export:
// dist/meshfix.cjs run once more (with a WebAssembly instance of its own),
// `names` from its top level exported beside its API as `scope`, and
// `scope.wasm` what the load made of the WebAssembly.
export function bundleScope(names) {
    const source = readFileSync(join(jsDir, 'dist/meshfix.cjs'), 'utf8');
    const module = { exports: {} };
    const scope = `\nmodule.exports.scope = { ${names.join(', ')}, get wasm() { return wasm; } };\n`;
    new Function('module', 'exports', 'require', source + scope)(module, module.exports, createRequire(import.meta.url));
    return module.exports;
}

// meshfix.h's MESHFIX_RESULT_LIST, read from the header: [{ name, text }] by value.
export function headerResults() {
    const header = readFileSync(join(jsDir, '..', 'meshfix.h'), 'utf8');
    const start = header.indexOf('#define MESHFIX_RESULT_LIST(X)');
    const list = header.slice(start, header.indexOf('\n\n', start));
    return [...list.matchAll(/X\((MESHFIX_\w+), "((?:[^"\\]|\\.)*)"\)/g)].map((m) => ({ name: m[1], text: m[2] }));
}

// The properties meshfix.d.ts declares in `export interface NAME { ... }`, as
// paths: a property whose type is an object literal ({ ... }) by its own.
export function declaredFields(name) {
    const types = readFileSync(join(jsDir, 'meshfix.d.ts'), 'utf8');
    const start = types.indexOf(`export interface ${name} `);
    if (start < 0)
        return [];
    const body = types.slice(types.indexOf('{', start) + 1);
    const paths = [], groups = [];
    let depth = 0;
    for (const line of body.split('\n')) {
        const code = line.replace(/\/\*.*?\*\/|\/\/.*$/g, '');
        const property = code.match(/^\s*(\w+)\??:\s*(\{?)/);
        if (property && depth === groups.length && !code.trim().startsWith('*')) {
            if (property[2] === '{' && !code.includes('}'))
                groups.push(property[1]);
            else
                paths.push([...groups, property[1]].join('.'));
        }
        depth += (code.match(/\{/g) || []).length - (code.match(/\}/g) || []).length;
        if (depth < 0) // the interface's own }
            break;
        groups.length = Math.min(groups.length, depth);
    }
    return paths;
}

// mulberry32: small, seeded, the same on every machine.
export function random(seed) {
    let a = seed >>> 0;
    return () => {
        a = (a + 0x6d2b79f5) >>> 0;
        let t = a;
        t = Math.imul(t ^ (t >>> 15), t | 1);
        t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
        return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
    };
}

export function hash(text) {
    let h = 2166136261;
    for (let i = 0; i < text.length; ++i)
        h = Math.imul(h ^ text.charCodeAt(i), 16777619) >>> 0;
    return h;
}

// The triangles a primitive draws, [a, b, c] each, glTF 2.0 section 3.7.2.1.
export function drawnTriangles(primitive) {
    const mode = primitive.getMode();
    const indices = primitive.getIndices();
    const v = indices ? Array.from(indices.getArray()) : [...Array(primitive.getAttribute('POSITION').getCount()).keys()];
    const out = [];
    if (mode === 4) {
        for (let i = 0; i + 2 < v.length; i += 3)
            out.push([v[i], v[i + 1], v[i + 2]]);
    } else if (mode === 5) {
        for (let i = 0; i + 2 < v.length; ++i)
            out.push(i % 2 === 0 ? [v[i], v[i + 1], v[i + 2]] : [v[i], v[i + 2], v[i + 1]]);
    } else if (mode === 6) {
        for (let i = 1; i + 1 < v.length; ++i)
            out.push([v[i], v[i + 1], v[0]]);
    }
    return out;
}

export function isTriangleMode(mode) {
    return mode === 4 || mode === 5 || mode === 6;
}

// The native reference: test/native_orient.c over meshfix.h, built once per run.
export function buildNative() {
    const binary = join(buildDir, 'native_orient');
    execFileSync(process.env.CC || 'cc', ['-std=c99', '-O2', '-Wall', '-Wextra', '-I', join(jsDir, '..'),
        join(here, 'native_orient.c'), '-o', binary, '-lm'], { stdio: 'inherit' });
    return binary;
}

export const NATIVE_FIELDS = ['verdict', 'trianglesFlipped', 'patchesFlipped', 'patchesDoubtful', 'trianglesDoubtful',
    'edgesInconsistentBefore', 'mesh.patches', 'mesh.edgesInconsistent', 'mesh.components',
    'evidence.patchesByVolume', 'evidence.patchesByNormals', 'evidence.patchesKept', 'verdictBefore',
    'patchesInsideOutBefore'];
export const VERDICT_NUMBERS = { clean: 0, repaired: 1, doubtful: 2, 'not-orientable': 3, inconsistent: 4, 'inside-out': 5 };

// meshes: [{ indices: Uint32Array, positions: Float32Array, normals: Float32Array|null, policy }]
// Returns per mesh { status, values (by NATIVE_FIELDS), summary, flipped }.
export function runNative(binary, meshes, name) {
    const parts = [];
    for (const m of meshes) {
        const policy = Buffer.from(m.policy || 'auto'); // by name: the native build asks meshfix_policy_from_string
        const head = new Uint32Array([m.indices.length, m.positions.length / 3, policy.length, m.normals ? 1 : 0]);
        parts.push(Buffer.from(head.buffer), policy, Buffer.from(m.indices.buffer, m.indices.byteOffset, m.indices.byteLength),
            Buffer.from(m.positions.buffer, m.positions.byteOffset, m.positions.byteLength));
        if (m.normals)
            parts.push(Buffer.from(m.normals.buffer, m.normals.byteOffset, m.normals.byteLength));
    }
    const input = join(buildDir, `${name}.in`), output = join(buildDir, `${name}.out`);
    writeFileSync(input, Buffer.concat(parts));
    execFileSync(binary, [input, output], { stdio: 'inherit' });
    const data = readFileSync(output);
    const results = [];
    let at = 0;
    for (const m of meshes) {
        const status = data.readInt32LE(at);
        at += 4;
        const values = {};
        NATIVE_FIELDS.forEach((field, i) => (values[field] = data.readDoubleLE(at + 8 * i)));
        at += 8 * NATIVE_FIELDS.length;
        const length = data.readUInt32LE(at);
        at += 4;
        const summary = data.toString('utf8', at, at + length);
        at += length;
        const flipped = new Uint8Array(data.subarray(at, at + m.indices.length / 3));
        at += m.indices.length / 3;
        results.push({ status, values, summary, flipped });
    }
    return results;
}

export function field(object, path) {
    return path.split('.').reduce((o, k) => o[k], object);
}

// Compares a WebAssembly orient() result with the native one; returns problems.
export function compareWithNative(result, native, label) {
    const problems = [];
    if (native.status !== 0)
        return [`${label}: native status ${native.status}, WebAssembly succeeded`];
    let differ = 0, first = -1;
    for (let t = 0; t < native.flipped.length; ++t)
        if (native.flipped[t] !== result.flipped[t]) {
            differ++;
            if (first < 0)
                first = t;
        }
    if (differ)
        problems.push(`${label}: ${differ} triangles flipped differently (first: triangle ${first})`);
    for (const name of NATIVE_FIELDS) {
        let mine = field(result.report, name);
        if (name === 'verdict' || name === 'verdictBefore')
            mine = VERDICT_NUMBERS[mine];
        if (mine !== native.values[name])
            problems.push(`${label}: report.${name} ${mine} (WebAssembly) != ${native.values[name]} (native)`);
    }
    if (result.summary !== native.summary)
        problems.push(`${label}: summary "${result.summary}" != "${native.summary}"`);
    return problems;
}

// The Khronos glTF-Validator on bytes; externals (a .gltf's .bin and
// images) from `directory`, or from external(path) when given.
export async function validate(validator, bytes, uri, directory, external) {
    const result = await validator.validateBytes(new Uint8Array(bytes), {
        uri,
        maxIssues: 0,
        externalResourceFunction: (path) =>
            new Promise((resolve, reject) => {
                try {
                    const data = external ? external(decodeURIComponent(path)) : readFileSync(join(directory, decodeURIComponent(path)));
                    if (!data)
                        throw new Error(`no resource ${path}`);
                    resolve(new Uint8Array(data));
                } catch (error) {
                    reject(error.message);
                }
            }),
    });
    const errors = new Map();
    for (const m of result.issues.messages)
        if (m.severity === 0)
            errors.set(m.code, (errors.get(m.code) || 0) + 1);
    return { errors, numErrors: result.issues.numErrors, numWarnings: result.issues.numWarnings };
}

// Error codes (with counts) of `after` beyond those of `before`.
export function newErrors(before, after) {
    const added = [];
    for (const [code, count] of after.errors)
        if (count > (before.errors.get(code) || 0))
            added.push(`${code} x${count - (before.errors.get(code) || 0)}`);
    return added;
}
