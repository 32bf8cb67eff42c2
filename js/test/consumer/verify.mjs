// The test's side of the consumer check (run from js/test, with js/'s own
// dev dependencies): the consumer's repaired model is valid under the
// Khronos glTF-Validator, and its flips are the native build's.
//   node verify.mjs NATIVE_BINARY OUTPUT.glb REPORT.json
import { readFileSync } from 'node:fs';
import validator from 'gltf-validator';
import { compareWithNative, runNative, validate } from '../common.mjs';

const [native, output, reportFile] = process.argv.slice(2);
const consumer = JSON.parse(readFileSync(reportFile, 'utf8'));
const check = await validate(validator, readFileSync(output), 'output.glb', null, () => null);
const meshes = consumer.meshes.map((m) => ({
    indices: new Uint32Array(m.indices), positions: new Float32Array(m.positions),
    normals: m.normals && new Float32Array(m.normals),
}));
const results = runNative(native, meshes, 'consumer_native');
const problems = consumer.meshes.flatMap((m, i) =>
    compareWithNative({ flipped: m.flipped, report: m.report, summary: m.summary }, results[i], `mesh ${i}`));
if (check.numErrors !== 0)
    problems.push(`validator: ${check.numErrors} errors: ${[...check.errors.keys()]}`);
if (consumer.trianglesFlipped === 0)
    problems.push('nothing was flipped');
const triangles = meshes.reduce((n, m) => n + m.indices.length / 3, 0);
console.log(`${meshes.length} meshes, ${triangles} triangles: ${consumer.trianglesFlipped} flipped, ` +
    `${problems.length ? problems.length + ' problems' : 'the same as native'}; validator ${check.numErrors} errors, ${check.numWarnings} warnings`);
for (const p of problems.slice(0, 20))
    console.log(`    ${p}`);
process.exit(problems.length ? 1 : 0);
