// Builds the browser page (page/) into a folder that any static file server,
// or the browser itself, can open: page/'s files, dist/meshfix.mjs (the
// WebAssembly inlined) and glTF-Transform's core with its one dependency,
// property-graph, copied from node_modules into vendor/ (their import of
// each other made relative). Nothing is fetched at run time.
//
//   node scripts/page.mjs [OUTPUT]    default: build/page beside package.json
//
// Needs dist/ (node scripts/build.mjs) and node_modules (npm ci).
import { copyFileSync, existsSync, mkdirSync, readdirSync, readFileSync, writeFileSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

const js = join(dirname(fileURLToPath(import.meta.url)), '..');
const out = resolve(process.argv[2] || join(js, 'build', 'page'));
const need = (file, how) => {
    if (!existsSync(file))
        throw new Error(`${file} is missing: ${how}`);
    return file;
};

mkdirSync(join(out, 'vendor'), { recursive: true });
for (const f of readdirSync(join(js, 'page')))
    if (/\.(html|js|css)$/.test(f))
        copyFileSync(join(js, 'page', f), join(out, f));
copyFileSync(need(join(js, 'dist', 'meshfix.mjs'), 'run node scripts/build.mjs'), join(out, 'meshfix.mjs'));

const modules = join(js, 'node_modules');
const core = readFileSync(need(join(modules, '@gltf-transform/core/dist/index.js'), 'run npm ci in js/'), 'utf8');
const graph = readFileSync(need(join(modules, 'property-graph/dist/index.mjs'), 'run npm ci in js/'), 'utf8');
const version = (name) => JSON.parse(readFileSync(join(modules, name, 'package.json'), 'utf8')).version;
const imports = core.match(/^(import|export)\b[^;]*?from\s*["'][^"']+["']/gm) || [];
if (imports.some((i) => !/["']property-graph["']/.test(i)))
    throw new Error(`@gltf-transform/core imports more than property-graph: ${imports.join(', ')}`);
const strip = (text) => text.replace(/\n\/\/# sourceMappingURL=.*\n?$/, '\n');
const banner = (name) => `// ${name} ${version(name)} (MIT), vendored from node_modules by meshfix-wasm's scripts/page.mjs\n`;
writeFileSync(join(out, 'vendor', 'gltf-transform-core.js'),
    banner('@gltf-transform/core') + strip(core).replace(/from\s*(["'])property-graph\1/g, 'from "./property-graph.js"'));
writeFileSync(join(out, 'vendor', 'property-graph.js'), banner('property-graph') + strip(graph));
copyFileSync(join(modules, '@gltf-transform/core/LICENSE.md'), join(out, 'vendor', 'gltf-transform-core.LICENSE.md'));
copyFileSync(join(modules, 'property-graph/LICENSE'), join(out, 'vendor', 'property-graph.LICENSE'));
// the page's .js files are ES modules (for node too: the tests import them from here)
writeFileSync(join(out, 'package.json'), '{ "type": "module", "private": true }\n');
console.log(`meshfix-wasm: the page is in ${out} (open index.html through a static server, e.g. python3 -m http.server)`);
