// The page: a dropped (or picked) file repaired here, drawn before and after,
// the report shown and the repaired file offered for download.
import { version } from './meshfix.mjs';
import { repairGltf } from './gltf_file.js';
import { repairMeshFile } from './mesh_files.js';
import { frame, render } from './render.js';

const $ = (id) => document.getElementById(id);
const drop = $('drop'), picker = $('file'), status = $('status');
let current = null; // { parts, view } of the file shown
let link = null;

function say(text, error = false) {
    status.textContent = text;
    status.className = error ? 'error' : '';
}

function draw() {
    if (current === null)
        return;
    const before = render($('before'), current.parts, current.view, { showFlipped: true });
    const after = render($('after'), current.parts.map((p) => ({ ...p, indices: p.repaired })), current.view);
    const hidden = before.rings > 0
        ? ` (${before.faceRed === 0 ? 'the flipped faces are hidden from this side' : 'the flipped faces are small'}: ` +
          `${before.rings} red ring${before.rings === 1 ? '' : 's'} mark${before.rings === 1 ? 's' : ''} where; drag to turn the model)`
        : '';
    $('pixels').textContent = `red pixels: before ${before.red}, after ${after.red}${hidden}`;
    document.body.dataset.redBefore = before.red;
    document.body.dataset.redAfter = after.red;
}

// the repaired triangles of a part: flipped ones with corners 2 and 3 swapped
function repairedIndices(part) {
    const out = Uint32Array.from(part.indices);
    for (let t = 0; 3 * t + 2 < out.length; ++t)
        if (part.flipped[t]) {
            out[3 * t + 1] = part.indices[3 * t + 2];
            out[3 * t + 2] = part.indices[3 * t + 1];
        }
    return out;
}

async function open(files) {
    files = Array.from(files);
    const main = files.find((f) => /\.(glb|gltf)$/i.test(f.name)) || files.find((f) => /\.(obj|stl|ply)$/i.test(f.name));
    if (!main) {
        say(`Not a file this page reads: ${files.map((f) => f.name).join(', ')} (OBJ, STL, PLY, glTF or GLB)`, true);
        return;
    }
    say(`Reading ${main.name} (${main.size.toLocaleString('en')} bytes)...`);
    document.body.dataset.state = 'working';
    const started = performance.now();
    try {
        const bytes = new Uint8Array(await main.arrayBuffer());
        let result;
        if (/\.(glb|gltf)$/i.test(main.name)) {
            const resources = new Map();
            for (const f of files)
                if (f !== main)
                    resources.set(f.name, new Uint8Array(await f.arrayBuffer()));
            result = await repairGltf(main.name, bytes, resources);
            result.up = 1;
        } else {
            result = await repairMeshFile(main.name, bytes);
        }
        const parts = result.parts.map((p) => ({ ...p, repaired: repairedIndices(p) }));
        current = { parts, flips: result.flips, view: { ...frame(parts, result.up), yaw: 35, pitch: 25 } };
        draw();
        const ms = Math.round(performance.now() - started);
        $('summary').textContent = `${main.name}: ${result.summary}`;
        $('details').textContent = [
            `${result.triangles.toLocaleString('en')} triangles, ${result.flips.toLocaleString('en')} ` +
            `${/\.(glb|gltf)$/i.test(main.name) ? 'triangles' : 'faces'} flipped, in ${ms} ms (meshfix.h ${version}, WebAssembly)`,
            result.byteExact
                ? `${result.outputName}: the input's bytes with only the flipped faces' corners reversed, as the meshfix command-line tool writes it`
                : `${result.outputName}: written by glTF-Transform (the document as repaired by the meshfix transform)`,
            '', ...result.lines,
        ].join('\n');
        if (link)
            URL.revokeObjectURL(link);
        link = URL.createObjectURL(new Blob([result.output], { type: 'application/octet-stream' }));
        const a = $('download');
        a.href = link;
        a.download = result.outputName;
        a.textContent = `Download ${result.outputName} (${result.output.length.toLocaleString('en')} bytes)`;
        a.hidden = false;
        say(`Done: ${main.name}`);
        document.body.dataset.state = 'done';
    } catch (error) {
        current = null;
        $('summary').textContent = '';
        $('details').textContent = '';
        $('download').hidden = true;
        say(`${main.name}: ${error && error.message ? error.message : error}`, true);
        document.body.dataset.state = 'error';
    }
}

drop.addEventListener('dragover', (e) => {
    e.preventDefault();
    drop.classList.add('over');
});
drop.addEventListener('dragleave', () => drop.classList.remove('over'));
drop.addEventListener('drop', (e) => {
    e.preventDefault();
    drop.classList.remove('over');
    if (e.dataTransfer && e.dataTransfer.files.length)
        open(e.dataTransfer.files);
});
picker.addEventListener('change', () => picker.files.length && open(picker.files));
// a file dropped beside the box opens too, instead of the browser navigating to it
window.addEventListener('dragover', (e) => e.preventDefault());
window.addEventListener('drop', (e) => {
    e.preventDefault();
    if (e.target !== drop && !drop.contains(e.target) && e.dataTransfer && e.dataTransfer.files.length)
        open(e.dataTransfer.files);
});

// drag a view to turn the model (both views together)
for (const canvas of [$('before'), $('after')]) {
    let from = null, pending = false;
    canvas.addEventListener('pointerdown', (e) => {
        from = [e.clientX, e.clientY];
        canvas.setPointerCapture(e.pointerId);
    });
    canvas.addEventListener('pointerup', () => (from = null));
    canvas.addEventListener('pointermove', (e) => {
        if (from === null || current === null)
            return;
        current.view.yaw -= (e.clientX - from[0]) * 0.5;
        current.view.pitch = Math.max(-89, Math.min(89, current.view.pitch + (e.clientY - from[1]) * 0.5));
        from = [e.clientX, e.clientY];
        if (!pending) {
            pending = true;
            requestAnimationFrame(() => {
                pending = false;
                draw();
            });
        }
    });
}
document.body.dataset.state = 'ready';
