// The C structs as the WebAssembly describes them (src/meshfix_wasm.c,
// mfjs_layout): the description parsed, checked before the first call,
// and fields read and written by it alone. A fragment before src/api.js
// (see scripts/build.mjs); nothing here calls the WebAssembly, so the
// tests can give the check a table of their own.

// DataView accessors by kind and element size; 'p' is a pointer, 'c' a char.
const LAYOUT_ACCESS = {
    u1: 'Uint8', u2: 'Uint16', u4: 'Uint32', u8: 'BigUint64',
    i1: 'Int8', i2: 'Int16', i4: 'Int32', i8: 'BigInt64',
    f4: 'Float32', f8: 'Float64', c1: 'Uint8', p4: 'Uint32', p8: 'BigUint64',
};
// The kinds src/api.js may ask a field to be (USES there).
const LAYOUT_KINDS = { integer: 'ui', float: 'f', pointer: 'p', char: 'c' };

// "visibility.min_samples" as JavaScript names it: "visibility.minSamples".
function camelCase(path) {
    return path.replace(/_([a-z0-9])/g, (_, c) => c.toUpperCase());
}

// mfjs_layout's lines ("meshfix_options visibility.rays 60 4 4 u") as
// { types: { size_t, pointer }, structs: { name: { size, fields, byPath } } };
// a field is { path, name, offset, size, element, kind, count }.
function parseLayout(text) {
    const layout = { types: {}, structs: {} };
    for (const line of text.split('\n').filter((l) => l !== '')) {
        const [owner, path, offset, size, element, kind] = line.split(' ');
        const field = { path, name: camelCase(path), offset: +offset, size: +size, element: +element, kind, count: size / element };
        if (owner === 'type') {
            layout.types[path] = field;
            continue;
        }
        const struct = layout.structs[owner] || (layout.structs[owner] = { size: null, fields: [], byPath: new Map() });
        if (path === '-') {
            struct.size = field.size;
        } else {
            struct.fields.push(field);
            struct.byPath.set(path, field);
        }
    }
    return layout;
}

function layoutDescribe(f) {
    return `${f.kind}${8 * f.element}${f.count !== 1 ? `[${f.count}]` : ''}`;
}

// Where C puts each field of a struct, from the sizes alone (natural
// alignment, as wasm32's ABI), against the offsets the compiler gave: a
// field of meshfix.h missing from the table shows as a hole or a short
// struct, as does a field listed out of order. Only a field small enough
// to sit in what was padding could hide.
function layoutTiling(name, struct) {
    const problems = [];
    const root = { children: new Map() };
    for (const f of struct.fields) { // nested structs ("mesh.triangles") as groups
        let node = root;
        for (const part of f.path.split('.').slice(0, -1)) {
            if (!node.children.has(part))
                node.children.set(part, { children: new Map() });
            node = node.children.get(part);
        }
        node.children.set(f.path, { field: f });
    }
    const align = (node) => (node.field ? node.field.element : Math.max(1, ...[...node.children.values()].map(align)));
    const up = (n, a) => Math.ceil(n / a) * a;
    const place = (node, cursor) => { // returns where the node ends
        if (node.field) {
            const f = node.field, at = up(cursor, f.element);
            if (f.offset !== at)
                problems.push(`${name}.${f.path} is at byte ${f.offset}, where C would put it after the fields listed before it is ${at}`);
            return f.offset + f.size;
        }
        const a = align(node);
        let end = up(cursor, a);
        for (const child of node.children.values())
            end = place(child, end);
        return up(end, a);
    };
    const end = place(root, 0);
    if (struct.size !== end)
        problems.push(`${name} is ${struct.size} bytes, its listed fields take ${end}`);
    return problems;
}

// What is wrong with a layout for src/api.js, nothing when it is sound:
// every field readable here and every struct tiled by its fields, and the
// fields `uses` names ({ struct: { path: 'integer' | 'float[3]' | ... } })
// there and of that kind.
function layoutProblems(layout, uses) {
    const problems = [];
    const pointer = layout.types.pointer;
    for (const type of ['size_t', 'pointer'])
        if (!(type in layout.types))
            problems.push(`no type ${type}`);
    for (const [name, struct] of Object.entries(layout.structs)) {
        let readable = true;
        for (const f of struct.fields) {
            if (!(f.kind + f.element in LAYOUT_ACCESS) || !Number.isInteger(f.count) || f.count < 1 ||
                (f.kind === 'p' && pointer !== undefined && f.element !== pointer.size)) {
                problems.push(`${name}.${f.path} is ${f.size} bytes of kind ${f.kind}, ${f.element} each: not a number or pointer read here`);
                readable = false;
            }
        }
        if (struct.size === null)
            problems.push(`${name} has fields but no size`);
        else if (readable)
            problems.push(...layoutTiling(name, struct));
    }
    for (const [name, paths] of Object.entries(uses)) {
        const struct = layout.structs[name];
        for (const [path, want] of Object.entries(paths)) {
            const f = struct === undefined ? undefined : struct.byPath.get(path);
            const [, kind, count] = want.match(/^(\w+)(?:\[(\d*)\])?$/);
            if (f === undefined)
                problems.push(`${name}.${path} is missing`);
            else if (!LAYOUT_KINDS[kind].includes(f.kind) || (count === undefined ? f.count !== 1 : count !== '' && +count !== f.count))
                problems.push(`${name}.${path} is ${layoutDescribe(f)}, taken here as ${want}`);
        }
    }
    return problems;
}

// The numbers a field holds; a float any finite value that stays finite
// in its size.
function fieldRange(f) {
    const bits = 8 * f.element;
    if (f.kind === 'u')
        return { least: 0, most: Math.min(2 ** bits - 1, Number.MAX_SAFE_INTEGER), integer: true };
    if (f.kind === 'i')
        return { least: -Math.min(2 ** (bits - 1), Number.MAX_SAFE_INTEGER), most: Math.min(2 ** (bits - 1) - 1, Number.MAX_SAFE_INTEGER), integer: true };
    return { least: -Number.MAX_VALUE, most: Number.MAX_VALUE, integer: false };
}

function fieldHolds(f, value) {
    const { least, most, integer } = fieldRange(f);
    return typeof value === 'number' && Number.isFinite(value) && (!integer || Number.isInteger(value)) &&
        value >= least && value <= most && (f.kind !== 'f' || f.element !== 4 || Number.isFinite(Math.fround(value)));
}

// "an unsigned 32-bit integer (0 to 4294967295)", for messages.
function fieldType(f) {
    const { least, most } = fieldRange(f);
    if (f.kind === 'f')
        return `a finite ${8 * f.element}-bit float`;
    return `${f.kind === 'u' ? 'an unsigned' : 'a signed'} ${8 * f.element}-bit integer (${least} to ${most})`;
}

function fieldAt(base, f, i) {
    return base + f.offset + i * f.element;
}

// A field of the struct at `base`: a number, an array of them, or (char[]) the text up to its first 0.
function getField(view, base, f) {
    const get = (i) => {
        const value = view[`get${LAYOUT_ACCESS[f.kind + f.element]}`](fieldAt(base, f, i), true);
        return typeof value === 'bigint' ? Number(value) : value;
    };
    if (f.kind === 'c') {
        const bytes = new Uint8Array(view.buffer, view.byteOffset + fieldAt(base, f, 0), f.count);
        const end = bytes.indexOf(0);
        return new TextDecoder().decode(end < 0 ? bytes : bytes.subarray(0, end));
    }
    return f.count === 1 ? get(0) : Array.from({ length: f.count }, (_, i) => get(i));
}

// Writes a number (or, for an array field, an array of them).
function setField(view, base, f, value) {
    const type = LAYOUT_ACCESS[f.kind + f.element];
    const values = f.count === 1 ? [value] : value;
    values.forEach((v, i) => view[`set${type}`](fieldAt(base, f, i), type.startsWith('Big') ? BigInt(v) : v, true));
}
