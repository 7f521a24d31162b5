import { inv3, matmul } from "./geometry.js";
// (one line: esm_source drops the lines that start with "import")
// A scene of textured planes rendered in the browser: the per-move work of lesson 01's
// pinhole_projection image (camlab.render.render for a sharp, undistorted grey scene seen by a
// camera at the origin). Each plane is its texture under a 3x3 map (canvas_from_texel), warped
// into a canvas supersampled `ss` times, composited far to near and box-filtered down. Twins are
// named beside each function; the warp samples as cv2.warpPerspective does (bilinear, positions
// rounded to 1/32 px, edges replicated), the coverage is the polygon's area per canvas pixel
// (cv2.fillConvexPoly with LINE_AA ramps over about one pixel instead).

const NEAR = 0.02; // camlab.render.model.NEAR: metres
const TAB = 32; // cv2's INTER_TAB_SIZE: warp positions in 1/32 px

// Twin: camlab.render.canvas._texture_level for even sizes (cv2.resize INTER_AREA to half: the
// mean of each 2x2 block). `tex` {data: Float32Array rows, width, height}; levels 0..n, cached.
export function textureLevel(levels, level) {
  while (levels.length <= level) {
    const a = levels[levels.length - 1];
    const w = Math.max(1, a.width >> 1), h = Math.max(1, a.height >> 1);
    const out = new Float32Array(w * h);
    for (let r = 0; r < h; r++) {
      const i0 = 2 * r * a.width, i1 = i0 + a.width;
      for (let c = 0; c < w; c++) {
        const k = 2 * c;
        out[r * w + c] = (a.data[i0 + k] + a.data[i0 + k + 1] + a.data[i1 + k] + a.data[i1 + k + 1]) * 0.25;
      }
    }
    levels.push({ data: out, width: w, height: h });
  }
  return levels[level];
}

// Twin: camlab.render.model.clip_to_near(extent, Rc, tc): the rectangle's part with z >= NEAR.
export function clipToNear([x0, y0, x1, y1], Rc, tc) {
  const rect = [[x0, y0], [x1, y0], [x1, y1], [x0, y1]];
  const z = rect.map(([x, y]) => x * Rc[2][0] + y * Rc[2][1] + tc[2] - NEAR);
  const out = [];
  for (let i = 0; i < 4; i++) {
    const a = rect[i], b = rect[(i + 1) % 4], za = z[i], zb = z[(i + 1) % 4];
    if (za >= 0) out.push(a);
    if (za >= 0 !== zb >= 0) out.push([a[0] + ((b[0] - a[0]) * za) / (za - zb), a[1] + ((b[1] - a[1]) * za) / (za - zb)]);
  }
  return out;
}

// Twin: camlab.render.model.metres_per_canvas_px(Hplane, poly).
export function metresPerCanvasPx(H, poly) {
  const n = poly.length;
  const mean = [poly.reduce((s, p) => s + p[0], 0) / n, poly.reduce((s, p) => s + p[1], 0) / n];
  let best = Infinity;
  for (const [x, y] of [...poly, mean]) {
    const q = H.map((row) => row[0] * x + row[1] * y + row[2]);
    const J = [0, 1].map((i) => [0, 1].map((j) => (H[i][j] * q[2] - q[i] * H[2][j]) / q[2] ** 2));
    const s = Math.sqrt(Math.abs(J[0][0] * J[1][1] - J[0][1] * J[1][0]));
    if (s > 0) best = Math.min(best, 1 / s);
  }
  return best;
}

// Twin: camlab.render.canvas.visible_planes for a camera at the origin (R = I, t = 0): each plane
// {R, t, extent, twoSided} seen, with its polygon, mean depth and canvas_from_plane map under Kc.
export function visiblePlanes(planes, Kc) {
  const seen = [];
  planes.forEach((p, index) => {
    const [x0, y0, x1, y1] = p.extent;
    const zs = [[x0, y0], [x1, y0], [x1, y1], [x0, y1]].map(([x, y]) => p.R[2][0] * x + p.R[2][1] * y + p.t[2]);
    if (Math.max(...zs) <= NEAR) return;
    if (!p.twoSided && p.R[0][2] * p.t[0] + p.R[1][2] * p.t[1] + p.R[2][2] * p.t[2] >= 0) return;
    const poly = clipToNear(p.extent, p.R, p.t);
    const depth = poly.reduce((s, [x, y]) => s + x * p.R[2][0] + y * p.R[2][1] + p.t[2], 0) / poly.length;
    const Hplane = matmul(Kc, p.R.map((row, i) => [row[0], row[1], p.t[i]]));
    seen.push({ index, plane: p, poly, depth, Hplane });
  });
  return seen;
}

// Twin: the level loop of camlab.render.canvas.draw_plane: the coarsest mipmap level whose texel
// still covers a canvas pixel where the plane is seen largest.
export function mipLevel(extent, width, height, mpp) {
  const [x0, , x1] = extent;
  let level = 0;
  while (level < 8 && (x1 - x0) / (width >> (level + 1) || 1) < mpp && width >> (level + 1) >= 2 && height >> (level + 1) >= 2) level += 1;
  return level;
}

// The share of canvas pixel (u, v) the convex polygon `quad` (canvas px, either orientation)
// covers: 4 x 4 samples.
function coverage(quad, u, v, orient) {
  let inside = 0;
  for (let i = 0; i < 4; i++) {
    const y = v - 0.375 + 0.25 * i;
    for (let j = 0; j < 4; j++) {
      const x = u - 0.375 + 0.25 * j;
      let ok = true;
      for (let k = 0; k < quad.length && ok; k++) {
        const a = quad[k], b = quad[(k + 1) % quad.length];
        ok = orient * ((b[0] - a[0]) * (y - a[1]) - (b[1] - a[1]) * (x - a[0])) >= 0;
      }
      inside += ok;
    }
  }
  return inside / 16;
}

// Twin: camlab.render.canvas.draw_plane(canvas, g, Kc, 0, False) for a grey texture: the plane's
// texture level under H = Hplane S sampled bilinearly inside its polygon's bounding box, and
// composited over `canvas` (Float32Array cw x ch) by its coverage.
export function drawPlane(canvas, cw, ch, g, levels) {
  const p = g.plane;
  const [x0, y0, x1, y1] = p.extent;
  const base = levels[0];
  const tex = textureLevel(levels, mipLevel(p.extent, base.width, base.height, metresPerCanvasPx(g.Hplane, g.poly)));
  const tw = tex.width, th = tex.height;
  const S = [[(x1 - x0) / tw, 0, x0 + (0.5 * (x1 - x0)) / tw], [0, (y1 - y0) / th, y0 + (0.5 * (y1 - y0)) / th], [0, 0, 1]];
  const M = inv3(matmul(g.Hplane, S)); // canvas px -> texel
  const quad = g.poly.map(([x, y]) => {
    const q = g.Hplane.map((row) => row[0] * x + row[1] * y + row[2]);
    return [q[0] / q[2], q[1] / q[2]];
  });
  let area = 0;
  quad.forEach((a, k) => {
    const b = quad[(k + 1) % quad.length];
    area += a[0] * b[1] - b[0] * a[1];
  });
  const orient = area > 0 ? 1 : -1;
  const us = quad.map((q) => q[0]), vs = quad.map((q) => q[1]);
  const u0 = Math.max(Math.floor(Math.min(...us)) - 2, 0), u1 = Math.min(Math.ceil(Math.max(...us)) + 3, cw);
  const v0 = Math.max(Math.floor(Math.min(...vs)) - 2, 0), v1 = Math.min(Math.ceil(Math.max(...vs)) + 3, ch);
  // each row's pixels whose centres lie more than 0.75 px inside every edge are wholly covered,
  // those more than 0.75 px outside any edge not at all: only the rest are sampled (coverage)
  const edges = quad.map((a, k) => {
    const b = quad[(k + 1) % quad.length];
    const len = Math.hypot(b[0] - a[0], b[1] - a[1]);
    return [(orient * -(b[1] - a[1])) / len, (orient * (b[0] - a[0])) / len, a[0], a[1]];
  });
  const span = (v, margin) => {
    let lo = u0, hi = u1 - 1; // pixels lo..hi have every edge's distance >= margin
    for (const [nx, ny, ax, ay] of edges) {
      const rest = margin - ny * (v - ay); // nx (u - ax) >= rest
      if (Math.abs(nx) < 1e-12) {
        if (rest > 0) return [1, 0];
      } else if (nx > 0) lo = Math.max(lo, Math.ceil(ax + rest / nx));
      else hi = Math.min(hi, Math.floor(ax + rest / nx));
    }
    return [lo, hi];
  };
  const data = tex.data;
  const [m0, m1, m2] = M[0], [m3, m4, m5] = M[1], [m6, m7, m8] = M[2];
  for (let v = v0; v < v1; v++) {
    const [o0, o1] = span(v, -0.75);
    if (o1 < o0) continue;
    const [i0, i1] = span(v, 0.75);
    const row = v * cw;
    for (let u = o0; u <= o1; u++) {
      const alpha = u >= i0 && u <= i1 ? 1 : coverage(quad, u, v, orient);
      if (alpha === 0) continue;
      const W = m6 * u + m7 * v + m8;
      const w = W ? TAB / W : 0;
      const X = Math.round((m0 * u + m1 * v + m2) * w);
      const Y = Math.round((m3 * u + m4 * v + m5) * w);
      const a = (X & (TAB - 1)) / TAB, b = (Y & (TAB - 1)) / TAB;
      const sx = X >> 5, sy = Y >> 5;
      let value;
      if (sx >= 0 && sy >= 0 && sx < tw - 1 && sy < th - 1) {
        const k = sy * tw + sx;
        value = (data[k] * (1 - a) + data[k + 1] * a) * (1 - b) + (data[k + tw] * (1 - a) + data[k + tw + 1] * a) * b;
      } else {
        const cx0 = Math.min(Math.max(sx, 0), tw - 1), cx1 = Math.min(Math.max(sx + 1, 0), tw - 1);
        const cy0 = Math.min(Math.max(sy, 0), th - 1) * tw, cy1 = Math.min(Math.max(sy + 1, 0), th - 1) * tw;
        value = (data[cy0 + cx0] * (1 - a) + data[cy0 + cx1] * a) * (1 - b) + (data[cy1 + cx0] * (1 - a) + data[cy1 + cx1] * a) * b;
      }
      const o = row + u;
      canvas[o] += alpha * (value - canvas[o]);
    }
  }
}

// Twin: camlab.render.render(planes, K, size, background=background, supersample=ss).irradiance
// for grey, sharp planes seen from the origin: the planes drawn far to near into the canvas,
// each output pixel the mean of its ss x ss canvas pixels, clipped to [0, 1]. `levels[i]` holds
// plane i's texture levels (textureLevel adds the coarser ones); `work` keeps the buffers.
export function renderPlanes(planes, levels, K, [w, h], ss = 2, background = 0.5, work = {}) {
  const s = ss;
  const Kc = matmul([[s, 0, (s - 1) / 2], [0, s, (s - 1) / 2], [0, 0, 1]], K);
  const cw = w * s, ch = h * s;
  if (!work.canvas || work.canvas.length !== cw * ch) work.canvas = new Float32Array(cw * ch);
  if (!work.image || work.image.length !== w * h) work.image = new Float32Array(w * h);
  const canvas = work.canvas.fill(background);
  const seen = visiblePlanes(planes, Kc).sort((a, b) => b.depth - a.depth);
  for (const g of seen) drawPlane(canvas, cw, ch, g, levels[g.index]);
  const out = work.image, k = 1 / (s * s);
  for (let v = 0; v < h; v++) {
    for (let u = 0; u < w; u++) {
      let sum = 0;
      for (let i = 0; i < s; i++) for (let j = 0; j < s; j++) sum += canvas[(v * s + i) * cw + u * s + j];
      out[v * w + u] = Math.min(1, Math.max(0, sum * k));
    }
  }
  return out;
}
