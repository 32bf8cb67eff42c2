// A new project's ES module use of the installed tarball: the
// glTF-Transform transform on a model whose winding was scrambled.
//   node gltf.mjs MODEL OUTPUT.glb REPORT.json
// Writes the repaired model and, for the test, what the library was given
// and answered per mesh (to compare with the native build).
import { writeFileSync } from 'node:fs';
import { Logger, NodeIO } from '@gltf-transform/core';
import { meshfix } from 'meshfix-wasm';

const [model, output, reportFile] = process.argv.slice(2);
const io = new NodeIO().setLogger(new Logger(Logger.Verbosity.ERROR));
const document = await io.read(model);
document.setLogger(new Logger(Logger.Verbosity.ERROR));

// scramble: every other triangle of every other indexed triangle list reversed
let reversed = 0;
document.getRoot().listMeshes().forEach((mesh, m) => {
    mesh.listPrimitives().forEach((primitive, p) => {
        const indices = primitive.getIndices();
        if (primitive.getMode() !== 4 || indices === null || (m + p) % 2 === 1)
            return;
        const array = indices.getArray().slice();
        for (let t = 0; 3 * t + 2 < array.length; t += 2, ++reversed)
            [array[3 * t + 1], array[3 * t + 2]] = [array[3 * t + 2], array[3 * t + 1]];
        indices.setArray(array);
    });
});

const meshes = [];
let report;
await document.transform(meshfix({
    onReport: (r) => (report = r),
    onMesh: (m) => meshes.push({
        indices: Array.from(m.indices), positions: Array.from(m.positions),
        normals: m.vertexNormals && Array.from(m.vertexNormals), flipped: Array.from(m.result.flipped),
        report: m.result.report, summary: m.result.summary,
    }),
}));
writeFileSync(output, await io.writeBinary(document));
writeFileSync(reportFile, JSON.stringify({ reversed, summary: report.summary, trianglesFlipped: report.trianglesFlipped, meshes }));
console.log(`reversed ${reversed}; ${report.summary}`);
