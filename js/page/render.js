// The page's renderer: triangles into a 2D canvas through a z-buffer of its
// own (no WebGL, so every browser, and a headless one without a GPU, draws
// the same pixels). Orthographic, a light at the eye.
//   grey   a face seen from its front
//   blue   a face seen from behind (its back: drawn, never culled)
//   red    a face the repair flips (the "before" view only), either side
// A part whose node mirrors (glTF, negative determinant) has its sides
// swapped, as a renderer's culling swaps them.

export const COLOURS = {
    front: [205, 205, 200],
    back: [70, 115, 235],
    flipped: [235, 35, 30],
    background: [255, 255, 255],
};

// Which RGBA pixel is which colour family: red (a flipped face), blue (a
// back face), or something else. The test counts pixels the same way.
export function pixelKind(r, g, b) {
    if (r > 60 && r > 2.5 * g && r > 2.5 * b)
        return 'red';
    if (b > 60 && b > 1.5 * r && b > 1.2 * g)
        return 'blue';
    return 'other';
}

// The camera for a set of parts: their bounds and the up axis (0 x, 1 y,
// 2 z); the view adds yaw and pitch in degrees. Each view fits the box's
// eight corners as they project.
export function frame(parts, up) {
    const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
    for (const part of parts)
        for (let v = 0; v < part.positions.length; v += 3)
            for (let k = 0; k < 3; ++k) {
                const x = part.positions[v + k];
                if (Number.isFinite(x)) {
                    lo[k] = Math.min(lo[k], x);
                    hi[k] = Math.max(hi[k], x);
                }
            }
    if (!(lo[0] <= hi[0]))
        return { lo: [-1, -1, -1], hi: [1, 1, 1], up };
    return { lo, hi, up };
}

// right, up and towards-the-eye unit vectors in world space
function basis(up, yawDeg, pitchDeg) {
    const yaw = (yawDeg * Math.PI) / 180, pitch = (pitchDeg * Math.PI) / 180;
    // in a frame where z is up: the eye at (cos p sin y, -cos p cos y, sin p)
    const eye = [Math.cos(pitch) * Math.sin(yaw), -Math.cos(pitch) * Math.cos(yaw), Math.sin(pitch)];
    const right = [Math.cos(yaw), Math.sin(yaw), 0];
    const top = [eye[1] * right[2] - eye[2] * right[1], eye[2] * right[0] - eye[0] * right[2], eye[0] * right[1] - eye[1] * right[0]];
    // z-up to the file's up: y up maps (x, y, z) -> (x, z, -y); x up maps to (z, x, y)
    const to = up === 2 ? (v) => v : up === 1 ? (v) => [v[0], v[2], -v[1]] : (v) => [v[2], v[0], v[1]];
    return { right: to(right), top: to(top), eye: to(eye) };
}

// Draws `parts` ({ positions, indices, flipped, mirrored }) into the canvas.
// With showFlipped, flipped faces are red, and when they cover fewer than
// RING_BELOW pixels (a small repair, or faces hidden from this side) each
// group of them gets a red ring too. Returns the pixel counts { red, blue,
// drawn } (red with the rings), faceRed (without) and rings.
export function render(canvas, parts, view, options = {}) {
    const width = canvas.width, height = canvas.height;
    const context = canvas.getContext('2d');
    const image = context.createImageData(width, height);
    const pixels = image.data;
    const depth = new Float32Array(width * height).fill(-Infinity);
    for (let i = 0; i < width * height; ++i) {
        pixels[4 * i] = COLOURS.background[0];
        pixels[4 * i + 1] = COLOURS.background[1];
        pixels[4 * i + 2] = COLOURS.background[2];
        pixels[4 * i + 3] = 255;
    }
    const { right, top, eye } = basis(view.up, view.yaw, view.pitch);
    const { lo, hi } = view;
    const [cx, cy, cz] = [0, 1, 2].map((k) => (lo[k] + hi[k]) / 2);
    let spanX = 0, spanY = 0;
    for (let corner = 0; corner < 8; ++corner) {
        const d = [0, 1, 2].map((k) => ((corner >> k) & 1 ? hi[k] - lo[k] : lo[k] - hi[k]) / 2);
        spanX = Math.max(spanX, Math.abs(d[0] * right[0] + d[1] * right[1] + d[2] * right[2]));
        spanY = Math.max(spanY, Math.abs(d[0] * top[0] + d[1] * top[1] + d[2] * top[2]));
    }
    const scale = 0.46 * Math.min(width / Math.max(spanX, 1e-30), height / Math.max(spanY, 1e-30));
    const showFlipped = !!options.showFlipped;
    const project = (x, y, z) => {
        x -= cx, y -= cy, z -= cz;
        return [width / 2 + scale * (x * right[0] + y * right[1] + z * right[2]),
            height / 2 - scale * (x * top[0] + y * top[1] + z * top[2])];
    };
    for (const part of parts) {
        const p = part.positions, n = p.length / 3;
        const sx = new Float32Array(n), sy = new Float32Array(n), sz = new Float32Array(n);
        for (let v = 0; v < n; ++v) {
            const x = p[3 * v] - cx, y = p[3 * v + 1] - cy, z = p[3 * v + 2] - cz;
            sx[v] = width / 2 + scale * (x * right[0] + y * right[1] + z * right[2]);
            sy[v] = height / 2 - scale * (x * top[0] + y * top[1] + z * top[2]);
            sz[v] = x * eye[0] + y * eye[1] + z * eye[2];
        }
        const idx = part.indices;
        for (let t = 0; 3 * t + 2 < idx.length; ++t) {
            const a = idx[3 * t], b = idx[3 * t + 1], c = idx[3 * t + 2];
            const ax = sx[a], ay = sy[a], bx = sx[b], by = sy[b], qx = sx[c], qy = sy[c];
            // twice the signed area on screen; y points down, so a front face (CCW as seen) is negative
            const area = (bx - ax) * (qy - ay) - (by - ay) * (qx - ax);
            if (!(area !== 0) || !Number.isFinite(area))
                continue;
            const front = (area < 0) !== !!part.mirrored;
            // the light at the eye: the face's slope towards the viewer
            const ux = p[3 * b] - p[3 * a], uy = p[3 * b + 1] - p[3 * a + 1], uz = p[3 * b + 2] - p[3 * a + 2];
            const wx = p[3 * c] - p[3 * a], wy = p[3 * c + 1] - p[3 * a + 1], wz = p[3 * c + 2] - p[3 * a + 2];
            const nx = uy * wz - uz * wy, ny = uz * wx - ux * wz, nz = ux * wy - uy * wx;
            const length = Math.hypot(nx, ny, nz);
            const facing = length > 0 ? Math.abs(nx * eye[0] + ny * eye[1] + nz * eye[2]) / length : 0;
            const shade = 0.45 + 0.55 * facing;
            const colour = showFlipped && part.flipped && part.flipped[t] ? COLOURS.flipped : front ? COLOURS.front : COLOURS.back;
            const r = colour[0] * shade, g = colour[1] * shade, bl = colour[2] * shade;
            const za = sz[a], zb = sz[b], zc = sz[c];
            const x0 = Math.max(0, Math.floor(Math.min(ax, bx, qx))), x1 = Math.min(width - 1, Math.ceil(Math.max(ax, bx, qx)));
            const y0 = Math.max(0, Math.floor(Math.min(ay, by, qy))), y1 = Math.min(height - 1, Math.ceil(Math.max(ay, by, qy)));
            const inv = 1 / area;
            for (let y = y0; y <= y1; ++y) {
                const py = y + 0.5;
                for (let x = x0; x <= x1; ++x) {
                    const px = x + 0.5;
                    // barycentric weights of the pixel centre
                    const w0 = ((bx - px) * (qy - py) - (by - py) * (qx - px)) * inv;
                    const w1 = ((qx - px) * (ay - py) - (qy - py) * (ax - px)) * inv;
                    const w2 = 1 - w0 - w1;
                    if (w0 < 0 || w1 < 0 || w2 < 0)
                        continue;
                    const z = w0 * za + w1 * zb + w2 * zc;
                    const at = y * width + x;
                    if (z <= depth[at])
                        continue;
                    depth[at] = z;
                    pixels[4 * at] = r;
                    pixels[4 * at + 1] = g;
                    pixels[4 * at + 2] = bl;
                }
            }
        }
    }
    let red = 0, blue = 0, drawn = 0;
    const count = () => {
        red = blue = drawn = 0;
        for (let i = 0; i < width * height; ++i) {
            drawn += depth[i] !== -Infinity;
            const kind = pixelKind(pixels[4 * i], pixels[4 * i + 1], pixels[4 * i + 2]);
            red += kind === 'red';
            blue += kind === 'blue';
        }
    };
    count();
    // flipped faces too small (or too hidden) to see: a red ring where each group of them is
    const faceRed = red;
    let rings = 0;
    if (showFlipped && red < RING_BELOW)
        rings = ringFlipped(parts, pixels, width, height, project);
    context.putImageData(image, 0, 0);
    if (rings === 0)
        return { red, blue, drawn, faceRed, rings };
    count();
    return { red, blue, drawn, faceRed, rings };
}

const RING_BELOW = 400; // red pixels of flipped faces below which they are ringed
const RING_RADIUS = 11;

// Rings (at most 64, none within a ring's diameter of another) around the
// flipped triangles' centres on screen; returns how many.
function ringFlipped(parts, pixels, width, height, project) {
    const centres = [];
    for (const part of parts) {
        if (!part.flipped)
            continue;
        const p = part.positions, idx = part.indices;
        for (let t = 0; 3 * t + 2 < idx.length && centres.length < 64; ++t) {
            if (!part.flipped[t])
                continue;
            const c = [0, 1, 2].map((k) => (p[3 * idx[3 * t] + k] + p[3 * idx[3 * t + 1] + k] + p[3 * idx[3 * t + 2] + k]) / 3);
            const [x, y] = project(c[0], c[1], c[2]);
            if (Number.isFinite(x) && Number.isFinite(y) && !centres.some(([u, v]) => Math.hypot(u - x, v - y) < 2 * RING_RADIUS))
                centres.push([x, y]);
        }
    }
    for (const [x, y] of centres)
        for (let py = Math.floor(y - RING_RADIUS - 2); py <= y + RING_RADIUS + 2; ++py)
            for (let px = Math.floor(x - RING_RADIUS - 2); px <= x + RING_RADIUS + 2; ++px) {
                if (px < 0 || py < 0 || px >= width || py >= height)
                    continue;
                const d = Math.hypot(px + 0.5 - x, py + 0.5 - y);
                if (d < RING_RADIUS - 1 || d > RING_RADIUS + 1)
                    continue;
                const at = 4 * (py * width + px);
                pixels[at] = COLOURS.flipped[0];
                pixels[at + 1] = COLOURS.flipped[1];
                pixels[at + 2] = COLOURS.flipped[2];
            }
    return centres.length;
}
