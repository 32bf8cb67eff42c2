// The browser page (page/, built by scripts/page.mjs) in Debian's Chromium,
// headless, driven by puppeteer-core:
//   node test/page.test.mjs CHROMIUM PAGE_DIR MESHFIX_CLI ENGINE_GLB [ASSIMP_MODELS]
// A static server of this file's own on 127.0.0.1 serves PAGE_DIR; every
// request the page makes must go to it. The scrambled engine (ENGINE_GLB
// with 30% of its triangles reversed by tests/cli/meshcheck.js, as
// tests/test_cli_files.sh scrambles it) is dropped on the page; the summary,
// the pixels of both views and the downloaded file are checked, the file
// byte for byte against the command-line tool's output for the same input.
// Then an STL is picked with the file input, the same way. Writes
// build/page-test/page.png (the engine) and page_stl.png (the STL),
// screenshots of the page as a user sees it.
import { execFileSync } from 'node:child_process';
import { createServer } from 'node:http';
import { existsSync, mkdirSync, mkdtempSync, readFileSync, rmSync, statSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { extname, join, normalize, resolve, sep } from 'node:path';
import { pathToFileURL } from 'node:url';
import puppeteer from 'puppeteer-core';
import { buildDir, failed, jsDir, report, test } from './common.mjs';

const [chromium, pageDir, cli, engine, models] = process.argv.slice(2);
const root = resolve(pageDir);
const meshcheck = join(jsDir, '..', 'tests', 'cli', 'meshcheck.js');
const out = join(buildDir, 'page-test');
rmSync(out, { recursive: true, force: true });
mkdirSync(out, { recursive: true });
const downloads = mkdtempSync(join(tmpdir(), 'meshfix-page-'));
const started = Date.now();

// ---- the static server: files under root, 127.0.0.1 only ----
const TYPES = { '.html': 'text/html; charset=utf-8', '.js': 'text/javascript', '.mjs': 'text/javascript',
    '.css': 'text/css', '.json': 'application/json', '.md': 'text/plain', '.LICENSE': 'text/plain' };
const served = [];
const server = createServer((request, response) => {
    const path = decodeURIComponent(new URL(request.url, 'http://127.0.0.1').pathname);
    const file = normalize(join(root, path === '/' ? 'index.html' : path));
    served.push(path);
    if (!(file === root || file.startsWith(root + sep)) || !existsSync(file) || !statSync(file).isFile()) {
        response.writeHead(404).end('not found');
        return;
    }
    response.writeHead(200, { 'content-type': TYPES[extname(file)] || 'application/octet-stream', 'cache-control': 'no-store' });
    response.end(readFileSync(file));
});
await new Promise((done) => server.listen(0, '127.0.0.1', done));
const origin = `http://127.0.0.1:${server.address().port}`;

// ---- the inputs and the command-line tool's outputs ----
function scrambled(input, name) {
    const file = join(out, name);
    execFileSync('node', [meshcheck, 'scramble', input, file, '11', '0.3']);
    const fixed = join(out, `cli_${name}`);
    const json = JSON.parse(execFileSync(cli, ['--json', file, fixed], { encoding: 'utf8' }));
    const flips = json.files[0].meshes.reduce((s, m) => s + m.flipped.faces, 0);
    return { file, fixed, flips };
}

// What the page's own modules draw under node for a file, on a canvas of
// the page's size (the views' pixels are the same in any JavaScript engine).
const pick = (n) => ({ red: n.red, blue: n.blue, background: n.background });
async function nodeRender(file, name) {
    const url = (f) => pathToFileURL(join(root, f)).href;
    const { repairGltf } = await import(url('gltf_file.js'));
    const { repairMeshFile } = await import(url('mesh_files.js'));
    const { frame, render, pixelKind } = await import(url('render.js'));
    const data = new Uint8Array(readFileSync(file));
    const r = /\.glb$/.test(name) ? { up: 1, ...(await repairGltf(name, data)) } : await repairMeshFile(name, data);
    const canvas = { width: 480, height: 360, pixels: null };
    canvas.getContext = () => ({
        createImageData: (w, h) => ({ data: new Uint8ClampedArray(4 * w * h) }),
        putImageData: (image) => (canvas.pixels = image.data),
    });
    const count = () => {
        const n = { red: 0, blue: 0, background: 0 }, d = canvas.pixels;
        for (let i = 0; i < d.length; i += 4) {
            const kind = pixelKind(d[i], d[i + 1], d[i + 2]);
            n.red += kind === 'red';
            n.blue += kind === 'blue';
            n.background += d[i] === 255 && d[i + 1] === 255 && d[i + 2] === 255;
        }
        return n;
    };
    const view = { ...frame(r.parts, r.up), yaw: 35, pitch: 25 };
    render(canvas, r.parts, view, { showFlipped: true });
    const before = count();
    const repaired = r.parts.map((p) => {
        const indices = Uint32Array.from(p.indices);
        for (let t = 0; t < p.flipped.length; ++t)
            if (p.flipped[t])
                [indices[3 * t + 1], indices[3 * t + 2]] = [p.indices[3 * t + 2], p.indices[3 * t + 1]];
        return { ...p, indices };
    });
    render(canvas, repaired, view);
    return { before, after: count() };
}

const browser = await puppeteer.launch({
    executablePath: chromium,
    headless: true,
    args: ['--no-sandbox', '--disable-gpu', '--no-first-run', '--no-default-browser-check', '--disable-extensions',
        '--disable-background-networking', '--disable-component-update', '--disable-sync',
        `--host-resolver-rules=MAP * ~NOTFOUND, EXCLUDE 127.0.0.1`],
});
const requests = [];
try {
    const page = await browser.newPage();
    await page.setViewport({ width: 1100, height: 900 });
    page.on('request', (r) => requests.push(r.url()));
    const errors = [];
    page.on('pageerror', (e) => errors.push(String(e)));
    page.on('console', (m) => m.type() === 'error' && errors.push(m.text()));
    const cdp = await page.createCDPSession();
    await cdp.send('Browser.setDownloadBehavior', { behavior: 'allow', downloadPath: downloads, eventsEnabled: true });

    await test('the page loads from 127.0.0.1 and is ready (the WebAssembly module imported)', async () => {
        await page.goto(`${origin}/index.html`, { waitUntil: 'load' });
        await page.waitForSelector('body[data-state="ready"]', { timeout: 20000 });
        return errors.slice();
    });

    // Returns what the page shows once it is done with a file.
    const shown = async () => {
        await page.waitForSelector('body[data-state="done"], body[data-state="error"]', { timeout: 60000 });
        return page.evaluate(async () => {
            const { pixelKind } = await import('./render.js');
            const count = (id) => {
                const c = document.getElementById(id);
                const data = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
                const n = { red: 0, blue: 0, background: 0, pixels: c.width * c.height };
                for (let i = 0; i < data.length; i += 4) {
                    const kind = pixelKind(data[i], data[i + 1], data[i + 2]);
                    n.red += kind === 'red';
                    n.blue += kind === 'blue';
                    n.background += data[i] === 255 && data[i + 1] === 255 && data[i + 2] === 255;
                }
                return n;
            };
            return {
                state: document.body.dataset.state, status: document.getElementById('status').textContent,
                summary: document.getElementById('summary').textContent,
                details: document.getElementById('details').textContent,
                before: count('before'), after: count('after'),
                download: document.getElementById('download').getAttribute('download'),
            };
        });
    };
    const download = async (name) => {
        const target = join(downloads, name);
        rmSync(target, { force: true });
        const done = new Promise((resolve_, reject) => {
            const timer = setTimeout(() => reject(new Error(`no download of ${name} within 30 s`)), 30000);
            cdp.on('Browser.downloadProgress', (e) => {
                if (e.state === 'completed') {
                    clearTimeout(timer);
                    resolve_();
                } else if (e.state === 'canceled') {
                    clearTimeout(timer);
                    reject(new Error('the download was canceled'));
                }
            });
        });
        await page.click('#download');
        await done;
        return readFileSync(target);
    };
    const compare = (got, want, name) => {
        if (Buffer.compare(got, want) === 0)
            return [];
        let at = 0;
        while (at < got.length && got[at] === want[at])
            ++at;
        return [`${name}: ${got.length} bytes, the CLI's ${want.length}; first difference at byte ${at}`];
    };

    // ---- the scrambled engine, dropped ----
    const glb = scrambled(engine, '2CylinderEngine.glb');
    let result = null;
    await test(`drop the scrambled 2CylinderEngine.glb (30% of its triangles reversed): the page repairs it`, async () => {
        const base64 = readFileSync(glb.file).toString('base64');
        await page.evaluate((name, data) => {
            const bytes = Uint8Array.from(atob(data), (c) => c.charCodeAt(0));
            const transfer = new DataTransfer();
            transfer.items.add(new File([bytes], name, { type: 'model/gltf-binary' }));
            const target = document.getElementById('drop');
            for (const type of ['dragenter', 'dragover', 'drop'])
                target.dispatchEvent(new DragEvent(type, { bubbles: true, cancelable: true, dataTransfer: transfer }));
        }, '2CylinderEngine.glb', base64);
        result = await shown();
        return result.state === 'done' ? [] : [`state ${result.state}: ${result.status}`];
    });
    if (result && result.state === 'done') {
        console.log(`    summary: ${result.summary}`);
        console.log(`    red pixels: before ${result.before.red}, after ${result.after.red}; blue (back faces): ` +
            `before ${result.before.blue}, after ${result.after.blue}; model pixels ` +
            `${result.before.pixels - result.before.background} of ${result.before.pixels}`);
        report(`the summary says what the CLI did: fixed ${glb.flips} triangles in 29 of 29 meshes`,
            result.summary === `2CylinderEngine.glb: fixed ${glb.flips} triangles in 29 of 29 meshes (34 primitives)`,
            result.summary);
        report('the report says the file is written as the CLI writes it', /as the meshfix command-line tool writes it/.test(result.details),
            result.details);
        report('before: the flipped faces are red (more than 5% of the model\'s pixels)',
            result.before.red > 0.05 * (result.before.pixels - result.before.background), JSON.stringify(result.before));
        report('after: no red pixel', result.after.red === 0, JSON.stringify(result.after));
        const node = await nodeRender(glb.file, '2CylinderEngine.glb');
        report(`the canvases hold the pixels the same renderer draws under node (red ${node.before.red} before, ` +
            `${node.after.red} after, blue ${node.before.blue} and ${node.after.blue})`,
            JSON.stringify(node) === JSON.stringify({ before: pick(result.before), after: pick(result.after) }),
            `browser ${JSON.stringify([result.before, result.after])}, node ${JSON.stringify(node)}`);
        report('after: the same silhouette (as many background pixels as before)',
            result.after.background === result.before.background, `${result.before.background} and ${result.after.background}`);
        await test(`the download, ${result.download}, is byte for byte the CLI's output for the same input`, async () =>
            compare(await download(result.download), readFileSync(glb.fixed), result.download));
        await page.screenshot({ path: join(out, 'page.png'), fullPage: true });
    }

    // ---- an STL, picked with the file input ----
    const stl = models && join(models, 'STL', 'Spider_binary.stl');
    if (stl && existsSync(stl)) {
        const spider = scrambled(stl, 'Spider_binary.stl');
        let picked = null;
        await test('pick a scrambled Spider_binary.stl with the file input: the page repairs it', async () => {
            await page.evaluate(() => (document.body.dataset.state = 'picking'));
            const input = await page.$('#file');
            await input.uploadFile(spider.file);
            picked = await shown();
            return picked.state === 'done' ? [] : [`state ${picked.state}: ${picked.status}`];
        });
        if (picked && picked.state === 'done') {
            console.log(`    summary: ${picked.summary}`);
            report(`the summary counts the faces the CLI flipped (${spider.flips})`,
                picked.summary.endsWith(`: ${spider.flips} of 1368 faces`), picked.summary);
            report('before red, after none', picked.before.red > 0 && picked.after.red === 0,
                `before ${picked.before.red}, after ${picked.after.red}`);
            await page.screenshot({ path: join(out, 'page_stl.png') });
            await test(`the download, ${picked.download}, is byte for byte the CLI's output`, async () =>
                compare(await download(picked.download), readFileSync(spider.fixed), picked.download));
        }
    }

    report('nothing was fetched but the page\'s own files from 127.0.0.1',
        requests.length > 0 && requests.every((u) => u.startsWith(`${origin}/`) || u.startsWith('blob:') || u.startsWith('data:')),
        requests.filter((u) => !u.startsWith(`${origin}/`)).join('\n'));
    report('no error in the page\'s console', errors.length === 0, errors.join('\n'));
} finally {
    await browser.close();
    server.close();
    rmSync(downloads, { recursive: true, force: true });
}
console.log(`    ${served.length} requests served, ${((Date.now() - started) / 1000).toFixed(1)} s; screenshot ${join(out, 'page.png')}`);
process.exit(failed() ? 1 : 0);
