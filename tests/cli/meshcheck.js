// Checks the command-line tool's outputs by parsing the files themselves,
// independently of the tool: what differs between two versions of a mesh
// file, and scrambled copies (faces reversed) to repair.
//
//   node tests/cli/meshcheck.js compare BEFORE AFTER [--normals]
//       prints "faces F flipped R normals N": F faces, R of them with their
//       corners reversed (the first kept first), N normals negated; exits 1
//       (naming the first difference) when anything else differs, or when
//       normals differ without --normals. STL: a reversed facet's normal is
//       negated with it. glTF: compared as documents (JSON with buffers,
//       accessors decoded; meshes by their triangles as the spec's modes
//       define them).
//   node tests/cli/meshcheck.js scramble IN OUT SEED FRACTION
//       writes IN with about FRACTION of its faces reversed (STL: vertex
//       order only, the stored normals kept); prints how many. glTF: indexed
//       triangle lists only, buffers rewritten beside OUT.
//   node tests/cli/meshcheck.js flip-normals IN OUT SEED FRACTION [--tangent-w]
//       writes IN with about FRACTION of its stored normals negated (OBJ vn
//       lines; glTF NORMAL elements of float accessors, buffers beside OUT;
//       with --tangent-w, TANGENT.w instead).
//   node tests/cli/meshcheck.js add-tangents IN.gltf OUT.gltf
//       adds TANGENT (xyz from the texture coordinates TEXCOORD_0, w the
//       handedness) to the primitives that have NORMAL and no TANGENT.
//   node tests/cli/meshcheck.js colours MARK.ply
//       prints "red R amber A other O": the faces of a --mark file by colour.
//   node tests/cli/meshcheck.js big-endian IN.ply OUT.ply
//       the same binary little-endian PLY, big-endian.
'use strict';
const fs = require('fs');
const path = require('path');

function fail(message) {
    console.log(`FAIL ${message}`);
    process.exit(1);
}

function random(seed) { // xorshift, so a scramble is the same on every run
    let s = seed >>> 0 || 1;
    return () => {
        s ^= s << 13; s >>>= 0;
        s ^= s >>> 17;
        s ^= s << 5; s >>>= 0;
        return s / 4294967296;
    };
}

const reversed = (list) => [list[0], ...list.slice(1).reverse()];
const same = (a, b) => a.length === b.length && a.every((x, i) => x === b[i]);
const negated = (a, b) => a.length === b.length && a.every((x, i) => Number(x) === -Number(b[i]) || (Number(x) === 0 && Number(b[i]) === 0));
const ext = (file) => path.extname(file).slice(1).toLowerCase();

// ---- text formats: OBJ and OFF, line by line ----

function lines(text) { return text.split('\n'); }
function tokens(line) { return line.replace(/#.*/, '').trim().split(/[ \t\r]+/).filter((t) => t !== ''); }

function compareObj(a, b, allowNormals) {
    const la = lines(a), lb = lines(b);
    if (la.length !== lb.length) fail(`line counts differ: ${la.length} and ${lb.length}`);
    const r = { faces: 0, flipped: 0, normals: 0 };
    for (let i = 0; i < la.length; ++i) {
        const ta = tokens(la[i]), tb = tokens(lb[i]);
        if (ta[0] === 'f') r.faces++;
        if (la[i] === lb[i]) continue;
        if (ta[0] === 'f' && tb[0] === 'f' && same(reversed(ta.slice(1)), tb.slice(1))) r.flipped++;
        else if (allowNormals && ta[0] === 'vn' && tb[0] === 'vn' && negated(ta.slice(1), tb.slice(1))) r.normals++;
        else fail(`line ${i + 1} differs: '${la[i]}' and '${lb[i]}'`);
    }
    return r;
}

function compareOff(a, b) {
    const la = lines(a), lb = lines(b);
    if (la.length !== lb.length) fail(`line counts differ: ${la.length} and ${lb.length}`);
    const r = { faces: 0, flipped: 0, normals: 0 };
    for (let i = 0; i < la.length; ++i) {
        const ta = tokens(la[i]), tb = tokens(lb[i]);
        const n = Number(ta[0]);
        const face = Number.isInteger(n) && n >= 3 && ta.length >= n + 1 && i > 1;
        if (la[i] === lb[i]) continue;
        if (face && same(reversed(ta.slice(1, n + 1)), tb.slice(1, n + 1)) && same(ta.slice(n + 1), tb.slice(n + 1))) r.flipped++;
        else fail(`line ${i + 1} differs: '${la[i]}' and '${lb[i]}'`);
    }
    r.faces = Number(tokens(la.find((l) => /^\s*\d/.test(l)))[1]);
    return r;
}

// ---- PLY ----

const plyTypes = { char: 'Int8', int8: 'Int8', uchar: 'Uint8', uint8: 'Uint8', short: 'Int16', int16: 'Int16',
    ushort: 'Uint16', uint16: 'Uint16', int: 'Int32', int32: 'Int32', uint: 'Uint32', uint32: 'Uint32',
    float: 'Float32', float32: 'Float32', double: 'Float64', float64: 'Float64' };
const plySize = { Int8: 1, Uint8: 1, Int16: 2, Uint16: 2, Int32: 4, Uint32: 4, Float32: 4, Float64: 8 };

// The header, and every element's rows: each property a value (or a list),
// with the byte offsets of binary values.
function parsePly(bytes) {
    const end = bytes.indexOf('end_header');
    const headerEnd = bytes.indexOf(10, end) + 1;
    const header = bytes.slice(0, headerEnd).toString('latin1');
    const elements = [];
    let format = 'ascii';
    for (const line of header.split('\n')) {
        const w = tokens(line);
        if (w[0] === 'format') format = w[1];
        else if (w[0] === 'element') elements.push({ name: w[1], count: Number(w[2]), properties: [], rows: [] });
        else if (w[0] === 'property' && w[1] === 'list') elements[elements.length - 1].properties.push({ name: w[4], count: plyTypes[w[2]], type: plyTypes[w[3]] });
        else if (w[0] === 'property') elements[elements.length - 1].properties.push({ name: w[2], type: plyTypes[w[1]] });
    }
    const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
    const little = format === 'binary_little_endian';
    let at = headerEnd;
    const words = format === 'ascii' ? bytes.slice(headerEnd).toString('latin1').split(/\s+/).filter((t) => t !== '') : null;
    let w = 0;
    const read = (type) => {
        if (words) return { value: Number(words[w++]) };
        const value = view[`get${type}`](at, little);
        const place = at;
        at += plySize[type];
        return { value, place };
    };
    for (const e of elements)
        for (let i = 0; i < e.count; ++i)
            e.rows.push(e.properties.map((p) => {
                if (!p.count) return read(p.type);
                const n = read(p.count).value;
                const values = [];
                for (let k = 0; k < n; ++k) values.push(read(p.type));
                return { list: values };
            }));
    return { header, format, elements, little };
}

function comparePly(a, b, allowNormals) {
    const pa = parsePly(a), pb = parsePly(b);
    if (pa.header !== pb.header) fail('PLY headers differ');
    if (a.length !== b.length && pa.format !== 'ascii') fail('binary PLY sizes differ');
    const r = { faces: 0, flipped: 0, normals: 0 };
    pa.elements.forEach((e, ei) => {
        const f = pb.elements[ei];
        if (e.rows.length !== f.rows.length) fail(`element ${e.name}: counts differ`);
        e.rows.forEach((row, i) => {
            let negatedHere = false;
            row.forEach((v, k) => {
                const p = e.properties[k], u = f.rows[i][k];
                if (v.list) {
                    const x = v.list.map((q) => q.value), y = u.list.map((q) => q.value);
                    if (e.name === 'face') r.faces++;
                    if (same(x, y)) return;
                    if (e.name === 'face' && same(reversed(x), y)) r.flipped++;
                    else fail(`element ${e.name} ${i} property ${p.name} differs`);
                } else if (!Object.is(v.value, u.value) && !(Number.isNaN(v.value) && Number.isNaN(u.value))) {
                    if (allowNormals && e.name === 'vertex' && /^n[xyz]$/.test(p.name) && v.value === -u.value) negatedHere = true;
                    else fail(`element ${e.name} ${i} property ${p.name}: ${v.value} and ${u.value}`);
                }
            });
            r.normals += negatedHere;
        });
    });
    return r;
}

function scramblePly(bytes, rnd, fraction) {
    const p = parsePly(bytes);
    const out = Buffer.from(bytes);
    let text = p.format === 'ascii' ? null : undefined, count = 0;
    const face = p.elements.find((e) => e.name === 'face');
    const picks = face.rows.map(() => rnd() < fraction);
    if (p.format === 'ascii') {
        // rebuild the face lines from their values: the scrambled file is an input, not a check
        const body = bytes.slice(bytes.indexOf(10, bytes.indexOf('end_header')) + 1).toString('latin1').split('\n');
        let line = p.elements.filter((e) => e !== face && p.elements.indexOf(e) < p.elements.indexOf(face)).reduce((s, e) => s + e.count, 0);
        face.rows.forEach((row, i) => {
            if (picks[i]) {
                body[line + i] = reverseTokens(body[line + i], 1, Number(tokens(body[line + i])[0]));
                count++;
            }
        });
        text = bytes.slice(0, bytes.indexOf(10, bytes.indexOf('end_header')) + 1).toString('latin1') + body.join('\n');
        return { data: Buffer.from(text, 'latin1'), count };
    }
    const view = new DataView(out.buffer, out.byteOffset, out.byteLength);
    face.rows.forEach((row, i) => {
        if (!picks[i]) return;
        const list = row.find((v) => v.list).list;
        const type = face.properties.find((q) => q.count).type;
        const values = reversed(list.map((q) => q.value));
        list.forEach((q, k) => view[`set${type}`](q.place, values[k], p.little));
        count++;
    });
    return { data: out, count };
}

function bigEndian(bytes) {
    const p = parsePly(bytes);
    if (p.format !== 'binary_little_endian') fail('not a binary little-endian PLY');
    const out = Buffer.from(bytes);
    const view = new DataView(out.buffer, out.byteOffset, out.byteLength);
    const src = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
    const flip = (type, place) => view[`set${type}`](place, src[`get${type}`](place, true), false);
    p.elements.forEach((e) => e.rows.forEach((row) => row.forEach((v, k) => {
        const prop = e.properties[k];
        if (v.list) {
            v.list.forEach((q) => flip(prop.type, q.place));
            // the list length precedes the first value
            if (v.list.length) flip(prop.count, v.list[0].place - plySize[prop.count]);
        } else flip(prop.type, v.place);
    })));
    const header = p.header.replace('binary_little_endian', 'binary_big_endian');
    return Buffer.concat([Buffer.from(header, 'latin1'), out.slice(Buffer.byteLength(p.header, 'latin1'))]);
}

// ---- STL ----

function stlFacets(bytes) {
    if (bytes.length >= 84 && bytes.length === 84 + 50 * bytes.readUInt32LE(80)) {
        const facets = [];
        for (let i = 0; i < bytes.readUInt32LE(80); ++i) {
            const o = 84 + 50 * i;
            const f = (k) => bytes.readFloatLE(o + 4 * k);
            facets.push({ normal: [f(0), f(1), f(2)], v: [[f(3), f(4), f(5)], [f(6), f(7), f(8)], [f(9), f(10), f(11)]],
                attribute: bytes.readUInt16LE(o + 48), offset: o });
        }
        return { binary: true, header: bytes.slice(0, 80), facets };
    }
    const t = bytes.toString('latin1').split(/\s+/);
    const facets = [];
    let normal = [0, 0, 0], v = [];
    for (let i = 0; i < t.length; ++i) {
        if (t[i] === 'normal') normal = [t[i + 1], t[i + 2], t[i + 3]];
        else if (t[i] === 'vertex') v.push([t[i + 1], t[i + 2], t[i + 3]]);
        else if (t[i] === 'endloop') { facets.push({ normal, v }); normal = [0, 0, 0]; v = []; }
    }
    return { binary: false, facets, words: t.filter((w) => !/^-?[0-9.eE+-]+$|^nan$|^inf$/i.test(w)).join(' ') };
}

function compareStl(a, b, allowNormals) {
    const sa = stlFacets(a), sb = stlFacets(b);
    if (sa.binary !== sb.binary || sa.facets.length !== sb.facets.length) fail('STL kind or facet counts differ');
    if (sa.binary && !sa.header.equals(sb.header)) fail('STL headers differ');
    if (!sa.binary && sa.words !== sb.words) fail('STL keywords differ');
    const r = { faces: sa.facets.length, flipped: 0, normals: 0 };
    const key = (v) => v.map(String).join(' ');
    sa.facets.forEach((f, i) => {
        const g = sb.facets[i];
        if (sa.binary && f.attribute !== g.attribute) fail(`facet ${i}: attribute bytes differ`);
        const sameCorners = f.v.every((c, k) => key(c) === key(g.v[k]));
        const swapped = key(f.v[0]) === key(g.v[0]) && key(f.v[1]) === key(g.v[2]) && key(f.v[2]) === key(g.v[1]);
        const sameNormal = key(f.normal) === key(g.normal), negatedNormal = negated(f.normal, g.normal);
        if (!sameCorners && !swapped) fail(`facet ${i}: corners differ otherwise than by a flip`);
        if (!sameNormal && !negatedNormal) fail(`facet ${i}: normal differs otherwise than by its sign`);
        r.flipped += !sameCorners;
        r.normals += !sameNormal;
        if (!sameNormal && sameCorners && !allowNormals) fail(`facet ${i}: normal negated without a flip`);
    });
    return r;
}

function scrambleStl(bytes, rnd, fraction) {
    const s = stlFacets(bytes);
    if (!s.binary) { // ASCII: swap the second and third vertex lines of a facet
        let count = 0, v = [];
        const out = lines(bytes.toString('latin1'));
        out.forEach((line, i) => {
            if (tokens(line)[0] === 'vertex') v.push(i);
            if (tokens(line)[0] !== 'endloop') return;
            if (v.length === 3 && rnd() < fraction) {
                [out[v[1]], out[v[2]]] = [out[v[2]], out[v[1]]];
                count++;
            }
            v = [];
        });
        return { data: Buffer.from(out.join('\n'), 'latin1'), count };
    }
    const out = Buffer.from(bytes);
    let count = 0;
    s.facets.forEach((f) => {
        if (rnd() >= fraction) return;
        bytes.copy(out, f.offset + 24, f.offset + 36, f.offset + 48);
        bytes.copy(out, f.offset + 36, f.offset + 24, f.offset + 36);
        count++;
    });
    return { data: out, count };
}

// ---- glTF ----

function loadGltf(file) {
    const bytes = fs.readFileSync(file);
    let json, bin = null;
    if (bytes.toString('latin1', 0, 4) === 'glTF') {
        let at = 12;
        while (at < bytes.length) {
            const length = bytes.readUInt32LE(at), type = bytes.readUInt32LE(at + 4);
            const chunk = bytes.slice(at + 8, at + 8 + length);
            if (type === 0x4E4F534A) json = JSON.parse(chunk.toString('utf8'));
            else if (type === 0x004E4942) bin = chunk;
            at += 8 + length;
        }
    } else json = JSON.parse(bytes.toString('utf8'));
    const buffers = (json.buffers || []).map((b, i) => {
        if (b.uri === undefined) return { data: Buffer.from(bin || []), source: 'glb' };
        if (b.uri.startsWith('data:')) return { data: Buffer.from(b.uri.slice(b.uri.indexOf(',') + 1), 'base64'), source: 'data' };
        const where = path.resolve(path.dirname(file), decodeURIComponent(b.uri));
        return { data: fs.readFileSync(where), source: where };
    });
    return { json, buffers, bytes };
}

const componentSize = { 5120: 1, 5121: 1, 5122: 2, 5123: 2, 5125: 4, 5126: 4 };
const componentGet = { 5120: 'getInt8', 5121: 'getUint8', 5122: 'getInt16', 5123: 'getUint16', 5125: 'getUint32', 5126: 'getFloat32' };
const widths = { SCALAR: 1, VEC2: 2, VEC3: 3, VEC4: 4, MAT2: 4, MAT3: 9, MAT4: 16 };

function decode(g, index) {
    const a = g.json.accessors[index];
    const width = widths[a.type], size = componentSize[a.componentType];
    const out = new Array(a.count * width).fill(0);
    const element = (viewIndex, offset, stride0) => {
        const v = g.json.bufferViews[viewIndex];
        const data = g.buffers[v.buffer].data;
        return { dv: new DataView(data.buffer, data.byteOffset + (v.byteOffset || 0) + (offset || 0)), stride: stride0 || v.byteStride || width * size };
    };
    if (a.bufferView !== undefined) {
        const e = element(a.bufferView, a.byteOffset);
        for (let i = 0; i < a.count; ++i)
            for (let k = 0; k < width; ++k) out[i * width + k] = e.dv[componentGet[a.componentType]](i * e.stride + k * size, true);
    }
    if (a.sparse) {
        const ii = element(a.sparse.indices.bufferView, a.sparse.indices.byteOffset, componentSize[a.sparse.indices.componentType]);
        const vv = element(a.sparse.values.bufferView, a.sparse.values.byteOffset, width * size);
        for (let s = 0; s < a.sparse.count; ++s) {
            const t = ii.dv[componentGet[a.sparse.indices.componentType]](s * componentSize[a.sparse.indices.componentType], true);
            for (let k = 0; k < width; ++k) out[t * width + k] = vv.dv[componentGet[a.componentType]](s * width * size + k * size, true);
        }
    }
    return out;
}

// The triangles of a primitive, as the spec defines them for its mode.
function triangles(g, p) {
    const mode = p.mode === undefined ? 4 : p.mode;
    const count = g.json.accessors[p.attributes.POSITION].count;
    const s = p.indices !== undefined ? decode(g, p.indices) : [...Array(count).keys()];
    const t = [];
    if (mode === 4) for (let i = 0; i + 2 < s.length; i += 3) t.push([s[i], s[i + 1], s[i + 2]]);
    else if (mode === 5) for (let i = 0; i + 2 < s.length; ++i) t.push(i % 2 ? [s[i], s[i + 2], s[i + 1]] : [s[i], s[i + 1], s[i + 2]]);
    else if (mode === 6) for (let i = 0; i + 2 < s.length; ++i) t.push([s[i + 1], s[i + 2], s[0]]);
    return { mode, t };
}

// JSON with the spec's defaults left out, so a writer that omits or adds
// them compares equal.
function normalise(value) {
    const defaults = { byteOffset: 0, normalized: false, doubleSided: false, alphaMode: 'OPAQUE', alphaCutoff: 0.5,
        texCoord: 0, scale: 1, strength: 1, metallicFactor: 1, roughnessFactor: 1, wrapS: 10497, wrapT: 10497,
        emissiveFactor: [0, 0, 0], baseColorFactor: [1, 1, 1, 1], rotation: [0, 0, 0, 1], translation: [0, 0, 0],
        matrix: [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1], interpolation: 'LINEAR', extras: {}, extensions: {} };
    if (Array.isArray(value)) return value.map((v) => normalise(v));
    if (value && typeof value === 'object') {
        const out = {};
        for (const k of Object.keys(value).sort()) {
            const v = normalise(value[k]);
            if (k in defaults && JSON.stringify(v) === JSON.stringify(defaults[k])) continue;
            if (k === 'scale' && JSON.stringify(v) === '[1,1,1]') continue; // a node's default scale
            out[k] = v;
        }
        return out;
    }
    return value;
}

function compareGltf(fa, fb, allowNormals) {
    const a = loadGltf(fa), b = loadGltf(fb);
    const r = { faces: 0, flipped: 0, normals: 0 };
    // everything but the binary plumbing and the meshes, as JSON
    for (const key of new Set([...Object.keys(a.json), ...Object.keys(b.json)])) {
        if (['accessors', 'bufferViews', 'buffers', 'meshes', 'images', 'skins', 'animations'].includes(key)) continue;
        if (JSON.stringify(normalise(a.json[key])) !== JSON.stringify(normalise(b.json[key]))) fail(`glTF '${key}' differs`);
    }
    // data behind accessors: skins and animations
    const sameAccessor = (i, j, what) => { if (!same(decode(a, i), decode(b, j))) fail(`${what}: data differs`); };
    (a.json.skins || []).forEach((s, i) => {
        const t = b.json.skins[i];
        if (!same(s.joints, t.joints) || s.skeleton !== t.skeleton) fail(`skin ${i} differs`);
        if (s.inverseBindMatrices !== undefined) sameAccessor(s.inverseBindMatrices, t.inverseBindMatrices, `skin ${i}`);
    });
    (a.json.animations || []).forEach((an, i) => {
        const bn = b.json.animations[i];
        if (JSON.stringify(normalise(an.channels)) !== JSON.stringify(normalise(bn.channels))) fail(`animation ${i} channels differ`);
        an.samplers.forEach((s, k) => {
            sameAccessor(s.input, bn.samplers[k].input, `animation ${i} sampler ${k} input`);
            sameAccessor(s.output, bn.samplers[k].output, `animation ${i} sampler ${k} output`);
        });
    });
    if ((a.json.images || []).length !== (b.json.images || []).length) fail('image counts differ');
    (a.json.meshes || []).forEach((m, mi) => {
        const n = b.json.meshes[mi];
        if (!n || m.primitives.length !== n.primitives.length) fail(`mesh ${mi}: primitives differ`);
        if (JSON.stringify(normalise(m.weights)) !== JSON.stringify(normalise(n.weights)) || m.name !== n.name) fail(`mesh ${mi} differs`);
        m.primitives.forEach((p, pi) => {
            const q = n.primitives[pi], where = `mesh ${mi} primitive ${pi}`;
            if (p.material !== q.material || !same(Object.keys(p.attributes).sort(), Object.keys(q.attributes).sort())) fail(`${where}: material or attributes differ`);
            for (const name of Object.keys(p.attributes)) {
                const x = decode(a, p.attributes[name]), y = decode(b, q.attributes[name]);
                if (same(x, y)) continue;
                if (!allowNormals || !['NORMAL', 'TANGENT'].includes(name) || !x.every((v, k) => v === y[k] || v === -y[k])) fail(`${where}: ${name} differs`);
                if (name === 'TANGENT') for (let k = 3; k < x.length; k += 4) r.tangents = (r.tangents || 0) + (x[k] !== y[k]);
                if (name === 'NORMAL') for (let k = 0; k < x.length; k += 3) r.normals += x[k] !== y[k] || x[k + 1] !== y[k + 1] || x[k + 2] !== y[k + 2];
            }
            (p.targets || []).forEach((t, ti) => {
                for (const name of Object.keys(t)) if (!same(decode(a, t[name]), decode(b, q.targets[ti][name]))) fail(`${where}: morph target ${ti} ${name} differs`);
            });
            const ta = triangles(a, p), tb = triangles(b, q);
            if (ta.t.length !== tb.t.length) fail(`${where}: triangle counts differ`);
            if (ta.mode !== tb.mode && !(tb.mode === 4)) fail(`${where}: mode changed to ${tb.mode}`);
            let flipped = 0;
            ta.t.forEach((t, i) => {
                const u = tb.t[i];
                if (same(t, u)) return;
                if (t[0] === u[0] && t[1] === u[2] && t[2] === u[1]) flipped++;
                else fail(`${where}: triangle ${i} is ${t} and ${u}`);
            });
            if (ta.mode !== tb.mode && flipped === 0) fail(`${where}: written as a list though nothing flipped`);
            r.faces += ta.t.length;
            r.flipped += flipped;
        });
    });
    return r;
}

function scrambleGltf(fin, fout, rnd, fraction) {
    const g = loadGltf(fin);
    let count = 0;
    for (const m of g.json.meshes || [])
        for (const p of m.primitives) {
            if ((p.mode !== undefined && p.mode !== 4) || p.indices === undefined || p.extensions) continue;
            const a = g.json.accessors[p.indices], v = g.json.bufferViews[a.bufferView];
            const size = componentSize[a.componentType], stride = v.byteStride || size;
            const data = g.buffers[v.buffer].data;
            const base = (v.byteOffset || 0) + (a.byteOffset || 0);
            for (let t = 0; t + 2 < a.count; t += 3) {
                if (rnd() >= fraction) continue;
                const o1 = base + (t + 1) * stride, o2 = base + (t + 2) * stride;
                const x = Buffer.from(data.slice(o1, o1 + size));
                data.copy(data, o1, o2, o2 + size);
                x.copy(data, o2);
                count++;
            }
        }
    writeGltf(g, fin, fout);
    return count;
}

// The JSON as it was, the buffers beside it (or in the GLB), images copied.
function writeGltf(g, fin, fout) {
    g.buffers.forEach((b, i) => {
        if (b.source === 'data') g.json.buffers[i].uri = `data:application/octet-stream;base64,${b.data.toString('base64')}`;
        else if (b.source !== 'glb') fs.writeFileSync(path.resolve(path.dirname(fout), g.json.buffers[i].uri), b.data);
    });
    for (const image of g.json.images || [])
        if (image.uri && !image.uri.startsWith('data:'))
            fs.copyFileSync(path.resolve(path.dirname(fin), decodeURIComponent(image.uri)), path.resolve(path.dirname(fout), decodeURIComponent(image.uri)));
    if (ext(fout) === 'glb') {
        const pad = (buf, byte) => Buffer.concat([buf, Buffer.alloc((4 - buf.length % 4) % 4, byte)]);
        const json = pad(Buffer.from(JSON.stringify(g.json)), 0x20);
        const bin = pad(g.buffers.find((b) => b.source === 'glb').data, 0);
        const head = Buffer.alloc(12);
        head.write('glTF', 0, 'latin1'); head.writeUInt32LE(2, 4); head.writeUInt32LE(12 + 8 + json.length + 8 + bin.length, 8);
        const chunk = (type, body) => { const h = Buffer.alloc(8); h.writeUInt32LE(body.length, 0); h.writeUInt32LE(type, 4); return Buffer.concat([h, body]); };
        fs.writeFileSync(fout, Buffer.concat([head, chunk(0x4E4F534A, json), chunk(0x004E4942, bin)]));
    } else fs.writeFileSync(fout, JSON.stringify(g.json, null, 2));
}

function flipNormals(fin, fout, rnd, fraction, tangentW) {
    if (ext(fin) === 'obj') {
        const r = scrambleText(fs.readFileSync(fin).toString('latin1'), rnd, fraction, (l) => tokens(l)[0] === 'vn',
            (l) => l.replace(/-?[0-9.]+(e[-+]?[0-9]+)?/gi, (x) => (Number(x) === 0 ? x : x[0] === '-' ? x.slice(1) : `-${x}`)));
        fs.writeFileSync(fout, r.data);
        return r.count;
    }
    const g = loadGltf(fin);
    let count = 0;
    const done = new Set();
    for (const m of g.json.meshes || [])
        for (const p of m.primitives) {
            const index = tangentW ? p.attributes.TANGENT : p.attributes.NORMAL;
            if (index === undefined || done.has(index)) continue;
            done.add(index);
            const a = g.json.accessors[index], v = g.json.bufferViews[a.bufferView];
            if (a.componentType !== 5126 || a.sparse) continue;
            const data = g.buffers[v.buffer].data, stride = v.byteStride || (tangentW ? 16 : 12);
            for (let i = 0; i < a.count; ++i) {
                if (rnd() >= fraction) continue;
                for (let k = tangentW ? 3 : 0; k < (tangentW ? 4 : 3); ++k) {
                    const o = (v.byteOffset || 0) + (a.byteOffset || 0) + i * stride + 4 * k;
                    const x = data.readFloatLE(o);
                    if (x !== 0) data.writeFloatLE(-x, o);
                }
                count++;
            }
        }
    writeGltf(g, fin, fout);
    return count;
}

// The line with tokens [from, from + n) in reverse order (the first kept
// first), the spaces between tokens as they were.
function reverseTokens(line, from, n) {
    const found = [...line.matchAll(/[^ \t\r]+/g)];
    const order = reversed(found.slice(from, from + n).map((m) => m[0]));
    let out = '', at = 0;
    found.forEach((m, i) => {
        out += line.slice(at, m.index) + (i >= from && i < from + n ? order[i - from] : m[0]);
        at = m.index + m[0].length;
    });
    return out + line.slice(at);
}

function addTangents(fin, fout) {
    const g = loadGltf(fin);
    const sub3 = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
    const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let added = 0;
    for (const m of g.json.meshes)
        for (const p of m.primitives) {
            if (!p.attributes.NORMAL || !p.attributes.TEXCOORD_0 || p.attributes.TANGENT) continue;
            const pos = decode(g, p.attributes.POSITION), nor = decode(g, p.attributes.NORMAL), uv = decode(g, p.attributes.TEXCOORD_0);
            const n = pos.length / 3, t = new Array(3 * n).fill(0), b = new Array(3 * n).fill(0);
            const v = (arr, i, w) => arr.slice(w * i, w * i + w);
            for (const [i0, i1, i2] of triangles(g, p).t) {
                const e1 = sub3(v(pos, i1, 3), v(pos, i0, 3)), e2 = sub3(v(pos, i2, 3), v(pos, i0, 3));
                const du1 = uv[2 * i1] - uv[2 * i0], dv1 = uv[2 * i1 + 1] - uv[2 * i0 + 1];
                const du2 = uv[2 * i2] - uv[2 * i0], dv2 = uv[2 * i2 + 1] - uv[2 * i0 + 1];
                const r = du1 * dv2 - dv1 * du2;
                if (r === 0) continue;
                for (const i of [i0, i1, i2])
                    for (let k = 0; k < 3; ++k) {
                        t[3 * i + k] += (e1[k] * dv2 - e2[k] * dv1) / r;
                        b[3 * i + k] += (e2[k] * du1 - e1[k] * du2) / r;
                    }
            }
            const out = Buffer.alloc(16 * n);
            for (let i = 0; i < n; ++i) {
                const N = v(nor, i, 3), T = v(t, i, 3), B = v(b, i, 3);
                const w = dot(cross(N, T), B) < 0 ? -1 : 1;
                [...T, w].forEach((x, k) => out.writeFloatLE(x, 16 * i + 4 * k));
            }
            const buffer = g.buffers[0];
            const offset = Math.ceil(buffer.data.length / 4) * 4;
            buffer.data = Buffer.concat([buffer.data, Buffer.alloc(offset - buffer.data.length), out]);
            g.json.buffers[0].byteLength = buffer.data.length;
            g.json.bufferViews.push({ buffer: 0, byteOffset: offset, byteLength: out.length, target: 34962 });
            g.json.accessors.push({ bufferView: g.json.bufferViews.length - 1, componentType: 5126, count: n, type: 'VEC4' });
            p.attributes.TANGENT = g.json.accessors.length - 1;
            added++;
        }
    writeGltf(g, fin, fout);
    return added;
}

// ---- scrambling text formats ----

function scrambleText(text, rnd, fraction, isFace, reverse) {
    let count = 0;
    const out = lines(text).map((line, i) => {
        if (!isFace(line, i) || rnd() >= fraction) return line;
        count++;
        return reverse(line);
    });
    return { data: Buffer.from(out.join('\n'), 'latin1'), count };
}

function main() {
    const [command, x, y, z, w] = process.argv.slice(2);
    if (command === 'compare') {
        const allow = process.argv.includes('--normals');
        const f = ext(x);
        const a = fs.readFileSync(x), b = fs.readFileSync(y);
        const r = f === 'obj' ? compareObj(a.toString('latin1'), b.toString('latin1'), allow)
            : f === 'off' ? compareOff(a.toString('latin1'), b.toString('latin1'))
            : f === 'ply' ? comparePly(a, b, allow)
            : f === 'stl' ? compareStl(a, b, allow)
            : compareGltf(x, y, allow);
        console.log(`faces ${r.faces} flipped ${r.flipped} normals ${r.normals}${r.tangents ? ` tangents ${r.tangents}` : ''}`);
    } else if (command === 'scramble') {
        const rnd = random(Number(z)), fraction = Number(w), f = ext(x);
        const data = fs.readFileSync(x);
        let r;
        if (f === 'obj') r = scrambleText(data.toString('latin1'), rnd, fraction, (l) => tokens(l)[0] === 'f',
            (l) => reverseTokens(l.replace(/#.*/, ''), 1, tokens(l).length - 1) + (l.includes('#') ? l.slice(l.indexOf('#')) : ''));
        else if (f === 'off') {
            const text = data.toString('latin1');
            const counts = tokens(lines(text).find((l, i) => i > 0 && /^\s*\d/.test(l)));
            const nv = Number(counts[0]);
            let seen = -1; // lines of numbers after the counts: vertices, then faces
            r = scrambleText(text, rnd, fraction, (l, i) => { if (i > 0 && /^\s*-?[\d.]/.test(l)) seen++; return seen > nv && /^\s*\d/.test(l); },
                (l) => reverseTokens(l, 1, Number(tokens(l)[0])));
        } else if (f === 'ply') r = scramblePly(data, rnd, fraction);
        else if (f === 'stl') r = scrambleStl(data, rnd, fraction);
        else { console.log(`scrambled ${scrambleGltf(x, y, rnd, fraction)}`); return; }
        fs.writeFileSync(y, r.data);
        console.log(`scrambled ${r.count}`);
    } else if (command === 'flip-normals') {
        console.log(`negated ${flipNormals(x, y, random(Number(z)), Number(w), process.argv.includes('--tangent-w'))}`);
    } else if (command === 'add-tangents') {
        console.log(`tangents added to ${addTangents(x, y)} primitives`);
    } else if (command === 'colours') {
        const face = parsePly(fs.readFileSync(x)).elements.find((e) => e.name === 'face');
        const c = { red: 0, amber: 0, other: 0 };
        for (const row of face.rows) {
            const rgb = row.slice(1).map((v) => v.value).join(' ');
            c[rgb === '230 30 30' ? 'red' : rgb === '255 176 0' ? 'amber' : 'other']++;
        }
        console.log(`red ${c.red} amber ${c.amber} other ${c.other}`);
    } else if (command === 'big-endian') {
        fs.writeFileSync(y, bigEndian(fs.readFileSync(x)));
    } else fail('usage: meshcheck.js compare A B [--normals] | scramble IN OUT SEED FRACTION | big-endian IN OUT');
}

main();
