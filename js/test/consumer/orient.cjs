// A new project's CommonJS use of the installed tarball: orient a mesh.
const { ready, orient, check } = require('meshfix-wasm');

ready.then(() => {
    const positions = new Float32Array([0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1]);
    const indices = new Uint32Array([0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 3, 2]); // the last face inside out
    const { indices: fixed, report, summary } = orient(indices, positions);
    const solid = check(fixed, positions, 'solid');
    console.log(`${summary}; check: ${solid.text}`);
    process.exit(report.trianglesFlipped === 1 && fixed[10] === 2 && solid.ok ? 0 : 1);
});
