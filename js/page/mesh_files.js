// The page's OBJ, STL and PLY: small readers of its own (the package has
// none), the package's orient() on the triangles, and the file written back
// as the command-line tool writes it: every byte as it was but the corners
// of the flipped faces, reversed with the first kept first (an STL facet's
// normal negated with it when it agreed with the old winding).
//
// What each format gives the library, as the tool gives it:
//   OBJ  a vertex per (v, vn) pair, the vn as vertex normals; polygons as a
//        fan from their first corner (the tool ear-clips concave ones)
//   STL  binary or ASCII; corners with the same x y z bits are one vertex
//        (-0 as +0), the facet normals as triangle normals
//   PLY  ascii, binary_little_endian, binary_big_endian; x y z, nx ny nz as
//        vertex normals, the face element's vertex_indices (or vertex_index)
// A face turns whole, the way most of its non-degenerate triangles turned.
import { orient, ready } from './meshfix.mjs';

const decoder = new TextDecoder('latin1');

// ---- text: lines and their tokens with where they are ----

// Tokens of each line: [{ text, begin, end }], lines ending at LF, CRLF or CR;
// '#' starts a comment (commentChar null: none).
function textLines(text, commentChar) {
    const lines = [];
    let tokens = [], at = 0;
    const n = text.length;
    while (at < n) {
        const c = text[at];
        if (c === '\n' || c === '\r') {
            lines.push(tokens);
            tokens = [];
            at += c === '\r' && text[at + 1] === '\n' ? 2 : 1;
            continue;
        }
        if (c === commentChar) {
            while (at < n && text[at] !== '\n' && text[at] !== '\r')
                ++at;
            continue;
        }
        if (c === ' ' || c === '\t' || c === '\f' || c === '\v') {
            ++at;
            continue;
        }
        const begin = at;
        while (at < n && !' \t\f\v\r\n'.includes(text[at]) && text[at] !== commentChar)
            ++at;
        tokens.push({ text: text.slice(begin, at), begin, end: at });
    }
    if (tokens.length)
        lines.push(tokens);
    return lines;
}

// Applies [{ begin, end, text }] edits (non-overlapping) to a latin1 string.
function applyEdits(text, edits) {
    edits.sort((a, b) => a.begin - b.begin);
    const out = [];
    let at = 0;
    for (const e of edits) {
        out.push(text.slice(at, e.begin), e.text);
        at = e.end;
    }
    out.push(text.slice(at));
    const joined = out.join('');
    const bytes = new Uint8Array(joined.length);
    for (let i = 0; i < joined.length; ++i)
        bytes[i] = joined.charCodeAt(i);
    return bytes;
}

// Corner i of n goes to slot reversedCorner(i, n): the first stays first.
const reversedCorner = (i, n) => (i === 0 ? 0 : n - i);

function reverseTokenEdits(corners, edits) {
    const n = corners.length;
    for (let i = 1; i < n; ++i) {
        const to = corners[reversedCorner(i, n)];
        edits.push({ begin: to.begin, end: to.end, text: corners[i].text });
    }
}

function negatedNumber(token) {
    const value = Number(token);
    if (!(value !== 0) || Number.isNaN(value))
        return token;
    if (token[0] === '-')
        return token.slice(1);
    if (token[0] === '+')
        return `-${token.slice(1)}`;
    return `-${token}`;
}

function number(token, what) {
    const value = Number(token);
    if (token === undefined || Number.isNaN(value) && !/^[+-]?nan/i.test(token))
        throw new Error(`bad ${what}: '${token === undefined ? '' : token}'`);
    return value;
}

// ---- one unit for the library: triangles of faces ----

class Unit {
    constructor() {
        this.positions = [];
        this.vertexNormals = null;
        this.triangleNormals = null;
        this.indices = [];
        this.triangleFace = [];
        this.faceCount = 0;
    }

    // a face of n >= 3 vertices, as a fan from its first corner
    addFace(vertices) {
        const face = this.faceCount++;
        for (let i = 1; i + 1 < vertices.length; ++i) {
            this.indices.push(vertices[0], vertices[i], vertices[i + 1]);
            this.triangleFace.push(face);
        }
        return face;
    }
}

// ---- OBJ ----

function readObj(bytes) {
    const text = decoder.decode(bytes);
    const lines = textLines(text, '#');
    const v = [], vn = [], faces = [];
    for (const tokens of lines) {
        const key = tokens.length ? tokens[0].text : '';
        if (key === 'v')
            v.push([number(tokens[1]?.text, 'v'), number(tokens[2]?.text, 'v'), number(tokens[3]?.text, 'v')]);
        else if (key === 'vn')
            vn.push([number(tokens[1]?.text, 'vn'), number(tokens[2]?.text, 'vn'), number(tokens[3]?.text, 'vn')]);
        else if (key === 'f')
            faces.push({ corners: tokens.slice(1), v: v.length, vn: vn.length });
    }
    const unit = new Unit();
    const pairs = new Map(); // "v/vn" -> library vertex
    const normals = [];
    let anyNormal = false;
    const resolve = (token, count, what) => {
        const i = parseInt(token, 10);
        const at = i < 0 ? count + i : i - 1;
        if (!Number.isInteger(i) || i === 0 || at < 0 || at >= count)
            throw new Error(`OBJ face ${what} index '${token}' out of range`);
        return at;
    };
    for (const face of faces) {
        if (face.corners.length < 3)
            continue;
        const vertices = face.corners.map((c) => {
            const parts = c.text.split('/');
            const p = resolve(parts[0], face.v, 'vertex');
            const n = parts.length > 2 && parts[2] !== '' ? resolve(parts[2], face.vn, 'normal') : -1;
            const key = `${p}/${n}`;
            let vertex = pairs.get(key);
            if (vertex === undefined) {
                vertex = pairs.size;
                pairs.set(key, vertex);
                unit.positions.push(...v[p]);
                normals.push(...(n >= 0 ? vn[n] : [0, 0, 0]));
                anyNormal = anyNormal || n >= 0;
            }
            return vertex;
        });
        face.face = unit.addFace(vertices);
    }
    if (anyNormal)
        unit.vertexNormals = normals;
    const kept = faces.filter((f) => f.face !== undefined);
    return {
        format: 'obj', up: 1, unit,
        write(faceFlipped) {
            const edits = [];
            for (const f of kept)
                if (faceFlipped[f.face])
                    reverseTokenEdits(f.corners, edits);
            return applyEdits(text, edits);
        },
    };
}

// ---- STL ----

function stlIsBinary(bytes) {
    if (bytes.length < 84)
        return false;
    const count = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength).getUint32(80, true);
    if (84 + 50 * count === bytes.length)
        return true;
    let start = 0;
    if (bytes[0] === 0xef && bytes[1] === 0xbb && bytes[2] === 0xbf)
        start = 3;
    while (start < bytes.length && ' \t\r\n'.includes(String.fromCharCode(bytes[start])))
        ++start;
    return decoder.decode(bytes.subarray(start, start + 5)).toLowerCase() !== 'solid';
}

// corners with the same bits are one vertex (-0 as +0)
function weldCorners(corners) {
    const key = new Float32Array(3), bits = new Uint32Array(key.buffer);
    const seen = new Map(), positions = [], indices = [];
    for (let i = 0; i < corners.length; i += 3) {
        key[0] = corners[i] === 0 ? 0 : corners[i];
        key[1] = corners[i + 1] === 0 ? 0 : corners[i + 1];
        key[2] = corners[i + 2] === 0 ? 0 : corners[i + 2];
        const k = `${bits[0]},${bits[1]},${bits[2]}`;
        // NaN corners are each their own vertex
        let vertex = Number.isNaN(key[0] + key[1] + key[2]) ? undefined : seen.get(k);
        if (vertex === undefined) {
            vertex = positions.length / 3;
            if (!Number.isNaN(key[0] + key[1] + key[2]))
                seen.set(k, vertex);
            positions.push(corners[i], corners[i + 1], corners[i + 2]);
        }
        indices.push(vertex);
    }
    return { positions, indices };
}

function readStl(bytes) {
    const unit = new Unit();
    const corners = [], normals = [];
    let text = null, facetText = [];
    const binary = stlIsBinary(bytes);
    if (binary) {
        const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
        const count = view.getUint32(80, true);
        if (84 + 50 * count > bytes.length)
            throw new Error(`STL: ${count} facets need ${84 + 50 * count} bytes, the file has ${bytes.length}`);
        for (let f = 0; f < count; ++f) {
            const at = 84 + 50 * f;
            for (let k = 0; k < 3; ++k)
                normals.push(view.getFloat32(at + 4 * k, true));
            for (let k = 3; k < 12; ++k)
                corners.push(view.getFloat32(at + 4 * k, true));
        }
    } else {
        text = decoder.decode(bytes);
        let facet = null;
        for (const tokens of textLines(text, null)) {
            const key = tokens.length ? tokens[0].text.toLowerCase() : '';
            if (key === 'facet') {
                facet = { normal: tokens.slice(2, 5), vertices: [] };
                for (let k = 0; k < 3; ++k)
                    normals.push(tokens[2 + k] ? number(tokens[2 + k].text, 'STL normal') : 0);
            } else if (key === 'vertex' && facet) {
                facet.vertices.push(tokens.slice(1, 4));
                for (let k = 1; k < 4; ++k)
                    corners.push(number(tokens[k]?.text, 'STL vertex'));
            } else if (key === 'endfacet' && facet) {
                if (facet.vertices.length !== 3)
                    throw new Error(`STL: a facet with ${facet.vertices.length} vertices`);
                facetText.push(facet);
                facet = null;
            }
        }
        // a vertex's text: from its first coordinate to its last
        facetText = facetText.map((f) => ({
            normal: f.normal,
            vertices: f.vertices.map((t) => ({ begin: t[0].begin, end: t[2].end, text: text.slice(t[0].begin, t[2].end) })),
        }));
    }
    const welded = weldCorners(Float32Array.from(corners));
    unit.positions = welded.positions;
    for (let f = 0; f < corners.length / 9; ++f)
        unit.addFace(welded.indices.slice(3 * f, 3 * f + 3));
    unit.triangleNormals = normals;
    return {
        format: 'stl', up: 2, unit,
        write(faceFlipped) {
            // a flipped facet's normal turns with it when it agreed with the old winding
            const negate = (f) => {
                const p = unit.positions, t = welded.indices;
                const a = 3 * t[3 * f], b = 3 * t[3 * f + 1], c = 3 * t[3 * f + 2];
                const u = [p[b] - p[a], p[b + 1] - p[a + 1], p[b + 2] - p[a + 2]];
                const w = [p[c] - p[a], p[c + 1] - p[a + 1], p[c + 2] - p[a + 2]];
                const n = [u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]];
                const dot = -(n[0] * normals[3 * f] + n[1] * normals[3 * f + 1] + n[2] * normals[3 * f + 2]);
                return dot < 0;
            };
            if (binary) {
                const out = new Uint8Array(bytes);
                for (let f = 0; f < faceFlipped.length; ++f) {
                    if (!faceFlipped[f])
                        continue;
                    const at = 84 + 50 * f;
                    for (let k = 24; k < 36; ++k) {
                        const x = out[at + k];
                        out[at + k] = out[at + k + 12];
                        out[at + k + 12] = x;
                    }
                    if (negate(f))
                        for (let k = 0; k < 3; ++k)
                            out[at + 4 * k + 3] ^= 0x80;
                }
                return out;
            }
            const edits = [];
            facetText.forEach((facet, f) => {
                if (!faceFlipped[f])
                    return;
                const [, b, c] = facet.vertices;
                edits.push({ begin: b.begin, end: b.end, text: c.text }, { begin: c.begin, end: c.end, text: b.text });
                if (negate(f))
                    for (const s of facet.normal)
                        edits.push({ begin: s.begin, end: s.end, text: negatedNumber(s.text) });
            });
            return applyEdits(text, edits);
        },
    };
}

// ---- PLY ----

const PLY_TYPES = {
    char: ['Int8', 1], int8: ['Int8', 1], uchar: ['Uint8', 1], uint8: ['Uint8', 1],
    short: ['Int16', 2], int16: ['Int16', 2], ushort: ['Uint16', 2], uint16: ['Uint16', 2],
    int: ['Int32', 4], int32: ['Int32', 4], uint: ['Uint32', 4], uint32: ['Uint32', 4],
    float: ['Float32', 4], float32: ['Float32', 4], double: ['Float64', 8], float64: ['Float64', 8],
};

function plyType(name) {
    const t = PLY_TYPES[name];
    if (t === undefined)
        throw new Error(`PLY: unknown type '${name}'`);
    return t;
}

function readPlyHeader(bytes) {
    let at = 0;
    if (bytes[0] === 0xef && bytes[1] === 0xbb && bytes[2] === 0xbf)
        at = 3;
    const lines = [];
    for (;;) {
        let end = at;
        while (end < bytes.length && bytes[end] !== 0x0a && bytes[end] !== 0x0d)
            ++end;
        if (end >= bytes.length)
            throw new Error('PLY: the header has no end_header line');
        const words = decoder.decode(bytes.subarray(at, end)).trim().split(/\s+/).filter(Boolean);
        at = end + (bytes[end] === 0x0d && bytes[end + 1] === 0x0a ? 2 : 1);
        lines.push(words);
        if (words[0] === 'end_header')
            break;
    }
    if (!lines.length || lines[0][0] !== 'ply')
        throw new Error('not a PLY file');
    let format = null;
    const elements = [];
    for (const words of lines.slice(1)) {
        if (words[0] === 'format')
            format = words[1];
        else if (words[0] === 'element')
            elements.push({ name: words[1], count: parseInt(words[2], 10), properties: [] });
        else if (words[0] === 'property') {
            const element = elements[elements.length - 1];
            if (!element)
                throw new Error('PLY: a property before any element');
            if (words[1] === 'list')
                element.properties.push({ name: words[4], list: true, countType: plyType(words[2]), type: plyType(words[3]) });
            else
                element.properties.push({ name: words[2], list: false, type: plyType(words[1]) });
        }
    }
    if (!['ascii', 'binary_little_endian', 'binary_big_endian'].includes(format))
        throw new Error(`PLY: unknown format '${format}'`);
    return { format, elements, dataStart: at };
}

function readPly(bytes) {
    const header = readPlyHeader(bytes);
    const ascii = header.format === 'ascii';
    const little = header.format === 'binary_little_endian';
    const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
    const unit = new Unit();
    const faces = []; // per face: its corners (ascii: tokens; binary: { at, type })
    let text = null, tokens = null, next = 0;
    if (ascii) {
        text = decoder.decode(bytes);
        tokens = textLines(text.slice(0), null).flat().filter((t) => t.begin >= header.dataStart);
    }
    let at = header.dataStart;
    const read = (type) => { // one value, and where it was
        if (ascii) {
            const token = tokens[next++];
            if (token === undefined)
                throw new Error('PLY: the file ends early');
            return { value: number(token.text, 'PLY value'), place: token };
        }
        const [get, size] = type;
        if (at + size > bytes.length)
            throw new Error('PLY: the file ends early');
        const value = view[`get${get}`](at, little);
        const place = { at, type };
        at += size;
        return { value, place };
    };
    let vertexCount = 0, normals = null;
    for (const element of header.elements) {
        const names = element.properties.map((p) => p.name);
        if (element.name === 'vertex') {
            vertexCount = element.count;
            const x = names.indexOf('x'), y = names.indexOf('y'), z = names.indexOf('z');
            if (x < 0 || y < 0 || z < 0)
                throw new Error('PLY: the vertex element has no x, y and z');
            const nx = names.indexOf('nx'), ny = names.indexOf('ny'), nz = names.indexOf('nz');
            if (nx >= 0 && ny >= 0 && nz >= 0)
                normals = [];
            for (let i = 0; i < element.count; ++i) {
                const values = element.properties.map((p) => {
                    if (!p.list)
                        return read(p.type).value;
                    const n = read(p.countType).value;
                    for (let k = 0; k < n; ++k)
                        read(p.type);
                    return null;
                });
                unit.positions.push(values[x], values[y], values[z]);
                if (normals)
                    normals.push(values[nx], values[ny], values[nz]);
            }
        } else {
            for (let i = 0; i < element.count; ++i)
                for (const p of element.properties) {
                    if (!p.list) {
                        read(p.type);
                        continue;
                    }
                    const n = read(p.countType).value;
                    const corners = [];
                    for (let k = 0; k < n; ++k)
                        corners.push(read(p.type));
                    if (element.name === 'face' && (p.name === 'vertex_indices' || p.name === 'vertex_index')) {
                        for (const c of corners)
                            if (!(c.value >= 0 && c.value < vertexCount))
                                throw new Error(`PLY: face index ${c.value} out of range (${vertexCount} vertices)`);
                        const face = { corners: corners.map((c) => c.place) };
                        if (n >= 3)
                            face.face = unit.addFace(corners.map((c) => c.value));
                        faces.push(face);
                    }
                }
        }
    }
    unit.vertexNormals = normals;
    return {
        format: 'ply', up: 2, unit,
        write(faceFlipped) {
            const kept = faces.filter((f) => f.face !== undefined && faceFlipped[f.face]);
            if (ascii) {
                const edits = [];
                for (const f of kept)
                    reverseTokenEdits(f.corners, edits);
                return applyEdits(text, edits);
            }
            const out = new Uint8Array(bytes);
            for (const f of kept) {
                const n = f.corners.length;
                const copies = f.corners.map((c) => bytes.slice(c.at, c.at + c.type[1]));
                for (let i = 1; i < n; ++i)
                    out.set(copies[i], f.corners[reversedCorner(i, n)].at);
            }
            return out;
        },
    };
}

// ---- the repair ----

export function readMeshFile(name, bytes) {
    const ext = (name.match(/\.([^.]+)$/) || [])[1]?.toLowerCase();
    if (ext === 'obj')
        return readObj(bytes);
    if (ext === 'stl')
        return readStl(bytes);
    if (ext === 'ply')
        return readPly(bytes);
    throw new Error(`${name}: not an OBJ, STL, PLY, glTF or GLB file`);
}

// Repairs an OBJ, STL or PLY; returns what repairGltf returns.
export async function repairMeshFile(name, bytes) {
    await ready;
    const file = readMeshFile(name, bytes);
    const u = file.unit;
    const positions = Float64Array.from(u.positions);
    const indices = Uint32Array.from(u.indices);
    const evidence = {};
    if (u.vertexNormals)
        evidence.vertexNormals = Float32Array.from(u.vertexNormals);
    if (u.triangleNormals)
        evidence.triangleNormals = Float32Array.from(u.triangleNormals);
    const result = orient(indices, positions, { evidence });
    // each face turns the way most of its non-degenerate triangles did
    const turned = new Uint32Array(u.faceCount), kept = new Uint32Array(u.faceCount);
    for (let t = 0; t < u.triangleFace.length; ++t) {
        if (result.patchIds[t] === 0xffffffff)
            continue;
        (result.flipped[t] ? turned : kept)[u.triangleFace[t]]++;
    }
    const faceFlipped = new Uint8Array(u.faceCount);
    let faces = 0;
    for (let f = 0; f < u.faceCount; ++f)
        faces += faceFlipped[f] = turned[f] > kept[f] ? 1 : 0;
    const flipped = new Uint8Array(u.triangleFace.length);
    for (let t = 0; t < flipped.length; ++t)
        flipped[t] = faceFlipped[u.triangleFace[t]];
    const stem = name.replace(/\.[^.]+$/, '');
    const ext = name.slice(stem.length);
    return {
        output: file.write(faceFlipped), outputName: `${stem}.fixed${ext}`,
        summary: faces === 0 ? result.summary : `${result.summary}: ${faces} of ${u.faceCount} faces`,
        flips: faces, triangles: indices.length / 3, up: file.up, byteExact: true,
        lines: [`${file.format.toUpperCase()}: ${u.faceCount} faces, ${indices.length / 3} triangles, ` +
            `${positions.length / 3} vertices${u.vertexNormals || u.triangleNormals ? ', normals as evidence' : ''}; ` +
            `verdict ${result.report.verdict}`],
        parts: [{ positions: Float32Array.from(positions), indices, flipped, mirrored: false }],
    };
}
