// Compiled by tsc --noEmit in test.sh: meshfix.d.ts as a user's TypeScript sees it.
import { Document } from '@gltf-transform/core';
import { check, inspect, meshfix, MeshfixError, orient, ready, version, weld } from 'meshfix-wasm';
import type { CheckResult, GltfReport, OrientResult, Report } from 'meshfix-wasm';

export async function main(): Promise<void> {
    await ready;
    const positions = new Float32Array([0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1]);
    const fixed: OrientResult<Uint16Array> = orient(new Uint16Array([0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 3, 2]), positions, {
        policy: 'auto',
        topology: 'positions',
        evidence: { vertexNormals: new Float32Array(12), sigma: 3 },
    });
    const indices: Uint16Array = fixed.indices;
    const flipped: Uint8Array = fixed.flipped;
    const report: Report = fixed.report;
    const plain: Uint32Array = orient([0, 1, 2], [0, 0, 0, 1, 0, 0, 0, 1, 0]).indices;
    const why: CheckResult = check(indices, positions, ['closed', 'manifold']);
    const text: string = why.ok ? 'ok' : why.text;
    inspect(indices, positions, { components: true }).components?.forEach((c) => c.closed);
    weld(positions, 1e-6).remap.length;
    try {
        orient([0, 1, 9], positions);
    } catch (e) {
        if (e instanceof MeshfixError)
            console.log(e.code);
    }
    const document = new Document();
    await document.transform(meshfix({ policy: 'up', up: 'y', evidence: { sigma: 3 }, onReport: (r: GltfReport) => console.log(r.summary) }));
    console.log(version, flipped.length, report.verdict, plain.length, text);
}
