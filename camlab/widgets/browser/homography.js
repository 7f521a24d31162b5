import { clipLine, inv3, mapLines, mapPoints, matmul } from "./geometry.js";
// (one line: esm_source drops the lines that start with "import")
// The per-move arithmetic of lesson 07's browser-drawn demos: homographies, the transformation
// hierarchy and a picture warped by inverse mapping. As in geometry.js, every function has a numpy
// twin named beside it, and tests/test_browser_homography_parity.py runs both under node.

const IDENTITY = [[1, 0, 0], [0, 1, 0], [0, 0, 1]];

// Twin: camlab.homography.normalise_homography(H): H / h33, or H / ||H||_F when h33 is (nearly) 0.
export function normaliseHomography(H) {
  const n = Math.hypot(...H.flat());
  const k = Math.abs(H[2][2]) > 1e-8 * n ? H[2][2] : n;
  return H.map((row) => row.map((c) => c / k));
}

// Twin: camlab.homography.compose(*Hs): the product H1 H2 ... Hk (Hk applied first), normalised.
export function composeHomographies(...Hs) {
  return normaliseHomography(Hs.reduce((out, H) => matmul(out, H), IDENTITY));
}

function rot(theta) {
  const c = Math.cos(theta), s = Math.sin(theta);
  return [[c, -s], [s, c]];
}

function embed(A, tx, ty) {
  return [[A[0][0], A[0][1], tx], [A[1][0], A[1][1], ty], [0, 0, 1]];
}

// Twin: camlab.homography.hierarchy_matrix(group, theta=, scale=, shear=, aspect=, tx=, ty=, v=):
// the group's matrix from one set of parameters (radians, px), each group using only its own.
export function hierarchyMatrix(group, { theta = 0, scale = 1, shear = 0, aspect = 1, tx = 0, ty = 0, v = [0, 0] }) {
  if (group === "euclidean") return embed(rot(theta), tx, ty);
  if (group === "similarity") return embed(rot(theta).map((r) => r.map((c) => c * scale)), tx, ty);
  const D = [[scale * aspect, 0], [0, scale / aspect]];
  const A = embed(matmul(matmul(matmul(rot(theta), rot(-shear)), D), rot(shear)), tx, ty);
  if (group === "affine") return A;
  return composeHomographies(A, [[1, 0, 0], [0, 1, 0], [v[0], v[1], 1]]);
}

// Twin: camlab.homography.classify(H, tol): the smallest group holding H (reflections count as affine).
export function classifyHomography(H, tol = 1e-9) {
  const Hm = normaliseHomography(H);
  const w = Hm[2][2];
  if (Math.abs(w) < tol || Math.max(Math.abs(Hm[2][0]), Math.abs(Hm[2][1])) > tol * Math.abs(w)) return "projective";
  const [[a, b], [c, d]] = [[Hm[0][0] / w, Hm[0][1] / w], [Hm[1][0] / w, Hm[1][1] / w]];
  const AtA = [[a * a + c * c, a * b + c * d], [b * a + d * c, b * b + d * d]];
  const s2 = AtA[0][0];
  const off = Math.max(Math.abs(AtA[0][0] - s2), Math.abs(AtA[0][1]), Math.abs(AtA[1][0]), Math.abs(AtA[1][1] - s2));
  if (off > tol * Math.max(s2, 1) || a * d - b * c <= 0) return "affine";
  if (Math.abs(s2 - 1) > tol) return "similarity";
  return "euclidean";
}

// Twin: camlab.projective.map_polyline(H, points): the mapped samples, a NaN row inserted wherever
// w = h3 . x changes sign between two samples (the segment between them passes through infinity).
export function mapPolyline(H, points) {
  const mapped = mapPoints(H, points);
  const w = points.map(([x, y]) => x * H[2][0] + y * H[2][1] + H[2][2]);
  const out = [];
  mapped.forEach((p, i) => {
    if (i > 0 && Math.sign(w[i]) !== Math.sign(w[i - 1])) out.push([NaN, NaN]);
    out.push([p[0] + 0, p[1] + 0]);
  });
  return out;
}

// Twin: camlab.projective.splits_at_infinity(H, points): w changes sign across the polygon's corners.
export function splitsAtInfinity(H, points) {
  const w = points.map(([x, y]) => x * H[2][0] + y * H[2][1] + H[2][2]);
  return Math.min(...w) <= 0 && 0 <= Math.max(...w);
}

const DEGREE = Math.PI / 180;

// Twin: camlab.widgets.homographies.twins.hierarchy_view(values, fixed): Hg, H = C Hg P, the group
// holding Hg, the mapped grid (NaN after each edge), diagonal and vanishing line, and whether torn.
export function hierarchyView(v, fixed) {
  const Hg = hierarchyMatrix(v.group, {
    theta: v.theta * DEGREE,
    scale: v.scale,
    shear: v.phi * DEGREE,
    aspect: v.aspect,
    tx: v.tx,
    ty: v.ty,
    v: [v.v1 * 1e-3, v.v2 * 1e-3],
  });
  const H = composeHomographies(fixed.C, Hg, fixed.P);
  const grid = fixed.grid_lines.flatMap((line) => [...mapPolyline(H, line), [NaN, NaN]]);
  return {
    Hg,
    H,
    kind: classifyHomography(Hg),
    grid,
    diagonal: mapPoints(H, fixed.diagonal),
    vanishing: clipLine(mapLines(H, [[0, 0, 1]])[0], fixed.xlim, fixed.ylim),
    torn: splitsAtInfinity(H, fixed.corners),
  };
}

// The output pixels (a box [u0, u1) x [v0, v1)) that can see the source: the bounding box, widened
// by 2 px, of the image of the source's rectangle grown by one pixel (-1 to w, -1 to h: beyond it a
// bilinear sample reads only fill); the whole output when that rectangle meets the line H sends to
// infinity (its image is then not the quadrilateral of its corners).
function imageBox(H, iw, ih, w, h) {
  const corners = [[-1, -1], [iw, -1], [iw, ih], [-1, ih]];
  const ws = corners.map(([x, y]) => H[2][0] * x + H[2][1] * y + H[2][2]);
  if (!(ws.every((z) => z > 0) || ws.every((z) => z < 0))) return { u0: 0, u1: w, v0: 0, v1: h };
  const m = mapPoints(H, corners);
  const xs = m.map((p) => p[0]), ys = m.map((p) => p[1]);
  const clamp = (x, n) => Math.min(n, Math.max(0, x));
  return {
    u0: clamp(Math.floor(Math.min(...xs)) - 2, w),
    u1: clamp(Math.ceil(Math.max(...xs)) + 3, w),
    v0: clamp(Math.floor(Math.min(...ys)) - 2, h),
    v1: clamp(Math.ceil(Math.max(...ys)) + 3, h),
  };
}

// Twin: numpy.rint: to the nearest integer, halves to the even one.
function rint(x) {
  const r = Math.round(x);
  return r - x === 0.5 && r % 2 !== 0 ? r - 1 : r;
}

// The picture as warpPerspective takes it, from homography_scenes.picture_data's base64 bytes.
export function pictureFrom(p) {
  const data = Uint8Array.from(atob(p.data), (c) => c.charCodeAt(0));
  return { data, width: p.width, height: p.height, channels: p.channels };
}

// Twin: camlab.warp.warp_perspective(image, H, shape, interpolation, fill, method="numpy"): each
// output pixel (u, v) samples the source at H^-1 (u, v, 1), bilinear or nearest, in float32 step for
// step as numpy does it (Math.fround after each operation), source points beyond the line H sends to
// infinity reading `fill` (with `mirror`, as cv2.warpPerspective, mirrored through it: only w = 0
// reads `fill`); rounded half to even into `out` (RGBA, 4 bytes a pixel, alpha 255).
// `image` is {data (h * w * channels bytes, rows), width, height, channels}; `shape` [height, width].
export function warpPerspective(image, H, shape, interpolation = "bilinear", fill = 0, out = null, mirror = false) {
  const f = Math.fround;
  const { width: iw, height: ih, channels: nc, data } = image;
  const [h, w] = shape;
  const target = out || new Uint8ClampedArray(h * w * 4);
  const centre = [(iw - 1) / 2, (ih - 1) / 2, 1];
  const ref = H[2][2] !== 0 ? H[2][2] : H[2][0] * centre[0] + H[2][1] * centre[1] + H[2][2];
  const sign = Math.sign(ref || 1);
  const Hi = inv3(H).map((row) => row.map((c) => f(c * sign)));
  // the image as float32 planes with a one-pixel border of fill (camlab.warp._padded_planes)
  const W2 = iw + 2, plane = (ih + 2) * W2;
  const planes = new Float32Array(nc * plane).fill(f(fill));
  for (let y = 0; y < ih; y++) {
    for (let x = 0; x < iw; x++) {
      for (let c = 0; c < nc; c++) planes[c * plane + (y + 1) * W2 + x + 1] = data[(y * iw + x) * nc + c];
    }
  }
  const tiny = f(1e-30), xMax = f(iw + 0.999), yMax = f(ih + 0.999);
  // Only the output pixels in the box of the source's image (one pixel more each side, where the
  // border blends with fill) can differ from fill: the rest are set to fill at once.
  const box = imageBox(H, iw, ih, w, h);
  const level = Math.min(255, Math.max(0, rint(f(fill))));
  new Uint32Array(target.buffer, target.byteOffset, h * w).fill((0xff000000 | (level << 16) | (level << 8) | level) >>> 0);
  for (let v = box.v0; v < box.v1; v++) {
    const x0r = f(f(Hi[0][1] * v) + Hi[0][2]), y0r = f(f(Hi[1][1] * v) + Hi[1][2]), z0r = f(f(Hi[2][1] * v) + Hi[2][2]);
    for (let u = box.u0; u < box.u1; u++) {
      let X = f(x0r + f(Hi[0][0] * u)), Y = f(y0r + f(Hi[1][0] * u));
      const Z = f(z0r + f(Hi[2][0] * u));
      if (mirror ? Z !== 0 : Z > tiny) {
        const iz = f(1 / Z);
        X = f(X * iz);
        Y = f(Y * iz);
      } else {
        X = -2;
        Y = -2;
      }
      X = f(X + 1);
      Y = f(Y + 1);
      const o = (v * w + u) * 4;
      target[o + 3] = 255;
      if (interpolation === "nearest") {
        const i = Math.min(Math.max(Math.floor(f(Y + 0.5)), 0), ih + 1) * W2 + Math.min(Math.max(Math.floor(f(X + 0.5)), 0), iw + 1);
        for (let c = 0; c < 3; c++) target[o + c] = planes[(c % nc) * plane + i];
        continue;
      }
      X = Math.min(Math.max(X, 0), xMax);
      Y = Math.min(Math.max(Y, 0), yMax);
      const xi = Math.trunc(X), yi = Math.trunc(Y);
      const a = X - xi, b = Y - yi;
      const i = yi * W2 + xi;
      for (let c = 0; c < 3; c++) {
        const k = (c % nc) * plane + i;
        const p00 = planes[k], p10 = planes[k + 1], p01 = planes[k + W2], p11 = planes[k + W2 + 1];
        const top = f(p00 + f(f(p10 - p00) * a));
        const bottom = f(p01 + f(f(p11 - p01) * a));
        target[o + c] = Math.min(255, Math.max(0, rint(f(top + f(f(bottom - top) * b)))));
      }
    }
  }
  return target;
}

// Twin: cv2.resize(a, (dw, dh), interpolation=cv2.INTER_NEAREST), as camlab.widgets._transport keeps a
// shown image at the size it is shown: destination pixel x takes source floor(x * sw / dw) (clipped),
// rows likewise. `src` and `out` are RGBA, 4 bytes a pixel.
export function nearestResize(src, sw, sh, dw, dh, out = null) {
  const target = out || new Uint8ClampedArray(dw * dh * 4);
  const fx = 1 / (dw / sw), fy = 1 / (dh / sh);
  const cols = Array.from({ length: dw }, (_, x) => Math.min(Math.floor(x * fx), sw - 1));
  for (let y = 0; y < dh; y++) {
    const row = Math.min(Math.floor(y * fy), sh - 1) * sw;
    for (let x = 0; x < dw; x++) {
      const i = (row + cols[x]) * 4, o = (y * dw + x) * 4;
      target[o] = src[i];
      target[o + 1] = src[i + 1];
      target[o + 2] = src[i + 2];
      target[o + 3] = src[i + 3];
    }
  }
  return target;
}

// ------------------------------------------------------------------ forward versus inverse warping

// Twin: camlab.warp.forward_warp(image, H, shape, fill): each source pixel (u, v) pushed to the
// rounded pi(H (u, v, 1)), floor(x + 0.5), in row order (a later pixel overwrites an earlier one);
// output pixels no source pixel reaches keep `fill` (the holes). RGBA into `out`, alpha 255; a
// one-channel image is repeated into R, G and B. `image` as for warpPerspective.
export function forwardWarp(image, H, shape, fill = 0, out = null) {
  const { width: sw, height: sh, channels: nc, data } = image;
  const [h, w] = shape;
  const target = out || new Uint8ClampedArray(h * w * 4);
  const level = Math.min(255, Math.max(0, rint(fill)));
  new Uint32Array(target.buffer, target.byteOffset, h * w).fill((0xff000000 | (level << 16) | (level << 8) | level) >>> 0);
  for (let v = 0; v < sh; v++) {
    for (let u = 0; u < sw; u++) {
      const [x, y] = mapPoints(H, [[u, v]])[0];
      if (!Number.isFinite(x) || !Number.isFinite(y)) continue;
      const ui = Math.floor(x + 0.5), vi = Math.floor(y + 0.5);
      if (ui < 0 || ui >= w || vi < 0 || vi >= h) continue;
      const o = (vi * w + ui) * 4, i = (v * sw + u) * nc;
      for (let c = 0; c < 3; c++) target[o + c] = data[i + (c % nc)];
    }
  }
  return target;
}

// Twin: camlab.widgets.homographies.twins.covered_area(outline, shape): 1 where the pixel's centre
// lies inside the convex polygon `outline` or on its edge (every (b - a) x (p - a) of one sign).
export function coveredArea(outline, shape, out = null) {
  const [h, w] = shape;
  const mask = out || new Uint8Array(h * w);
  const n = outline.length;
  for (let v = 0; v < h; v++) {
    for (let u = 0; u < w; u++) {
      let pos = true, neg = true;
      for (let k = 0; k < n; k++) {
        const a = outline[k], b = outline[(k + 1) % n];
        const side = (b[0] - a[0]) * (v - a[1]) - (b[1] - a[1]) * (u - a[0]);
        pos = pos && side >= 0;
        neg = neg && side <= 0;
      }
      mask[v * w + u] = pos || neg ? 1 : 0;
    }
  }
  return mask;
}

// Twin: camlab.widgets.homographies.twins._painted_warps(forward, inverse, covered, reached, pulled,
// hole, outside), in place on the RGBA warps: the forward warp's holes `hole`, beyond the picture
// `outside` grey; the inverse warp `outside` where it pulled nothing. Masks: 1 byte a pixel.
export function paintWarps(forward, inverse, covered, reached, pulled, hole, outside) {
  for (let p = 0; p < covered.length; p++) {
    const o = p * 4;
    if (!covered[p]) forward.fill(outside, o, o + 3);
    else if (!reached[p]) forward.set(hole, o);
    if (!pulled[p]) inverse.fill(outside, o, o + 3);
  }
}

// The first channel of an RGBA image as a mask (1 where it is not 0).
function nonZero(rgba, out) {
  for (let p = 0; p < out.length; p++) out[p] = rgba[p * 4] > 0 ? 1 : 0;
  return out;
}

// Twin: camlab.widgets.homographies.twins.forward_inverse_view(values, picture, fixed): H = C S V P
// (S the sliders' similarity, V the fixed tilt), the mapped outline, both warps as shown (RGBA) and
// the covered, reached and pulled masks. `work` keeps the buffers between calls (optional).
export function forwardInverseView(v, picture, fixed, work = {}) {
  const S = hierarchyMatrix("similarity", { theta: v.angle * DEGREE, scale: v.scale });
  const V = [[1, 0, 0], [0, 1, 0], [fixed.tilt[0], fixed.tilt[1], 1]];
  const H = composeHomographies(fixed.C, S, V, fixed.P);
  const [h, w] = fixed.shape;
  if (!work.shown) {
    const ones = { data: new Uint8Array(picture.width * picture.height).fill(1), width: picture.width, height: picture.height, channels: 1 };
    Object.assign(work, { ones, shown: new Uint8ClampedArray(h * w * 4), inverse: new Uint8ClampedArray(h * w * 4), mark: new Uint8ClampedArray(h * w * 4) });
    Object.assign(work, { covered: new Uint8Array(h * w), reached: new Uint8Array(h * w), pulled: new Uint8Array(h * w) });
  }
  const outline = mapPoints(H, fixed.edges);
  coveredArea(outline, fixed.shape, work.covered);
  nonZero(forwardWarp(work.ones, H, fixed.shape, 0, work.mark), work.reached);
  nonZero(warpPerspective(work.ones, H, fixed.shape, "nearest", 0, work.mark), work.pulled);
  forwardWarp(picture, H, fixed.shape, 0, work.shown);
  warpPerspective(picture, H, fixed.shape, "nearest", 0, work.inverse);
  paintWarps(work.shown, work.inverse, work.covered, work.reached, work.pulled, fixed.hole, fixed.outside);
  return { H, outline, shown: work.shown, inverse: work.inverse, covered: work.covered, reached: work.reached, pulled: work.pulled };
}

// The rows top..top+height and columns left..left+width of an RGBA image `width` px wide.
export function cropPixels(rgba, width, [top, left, height, cols]) {
  const out = new Uint8ClampedArray(height * cols * 4);
  for (let r = 0; r < height; r++) out.set(rgba.subarray(((top + r) * width + left) * 4, ((top + r) * width + left + cols) * 4), r * cols * 4);
  return out;
}

// Twin: camlab.widgets._transport._nearest_at_centres(a, us, vs, box): the RGBA image `src` (sw x sh,
// rows from the bottom up, as Agg takes them) sampled at the centres of the canvas pixels of box
// [left, right, bottom, top] (display px, y up): column floor((x + 0.5 - us[0]) / (us[1] - us[0]) * sw),
// row likewise from vs, clipped; the result's rows from the bottom up too.
export function nearestAtCentres(src, sw, sh, us, vs, [left, right, bottom, top]) {
  const dw = right - left, dh = top - bottom;
  const pick = (x, lo, hi, n) => Math.min(Math.max(Math.floor(((x + 0.5 - lo) / (hi - lo)) * n), 0), n - 1);
  const cols = Array.from({ length: dw }, (_, i) => pick(left + i, us[0], us[1], sw));
  const out = new Uint8ClampedArray(dw * dh * 4);
  for (let r = 0; r < dh; r++) {
    const row = pick(bottom + r, vs[0], vs[1], sh) * sw;
    for (let c = 0; c < dw; c++) {
      for (let k = 0; k < 4; k++) out[(r * dw + c) * 4 + k] = src[(row + cols[c]) * 4 + k];
    }
  }
  return out;
}

// An RGBA image's rows in the other order (top-down <-> bottom-up).
function flipRows(rgba, width, height) {
  const out = new Uint8ClampedArray(rgba.length), n = width * 4;
  for (let r = 0; r < height; r++) {
    for (let k = 0; k < n; k++) out[(height - 1 - r) * n + k] = rgba[r * n + k];
  }
  return out;
}

// Twin: what camlab.widgets._transport draws for an image shown with interpolation="nearest"
// (show_at_display_resolution's set_data, then _screen_image): kept at most at its box's size
// (nearestResize, cv2's nearest shrink), then, where the box is larger, each canvas pixel takes the
// data pixel under its centre (nearestAtCentres). `place` is homography_scenes.image_place's: the
// box (canvas px), the extent's unrounded edges us, vs (display px) and the canvas height.
// Returns {data, width, height}: RGBA rows from the top, to draw at place.box.
export function liveImage(rgba, width, height, place) {
  const box = place.box;
  let data = rgba, w = width, h = height;
  const fw = Math.min(width, box.width), fh = Math.min(height, box.height);
  if (fw >= 2 && fh >= 2 && (fw !== width || fh !== height)) {
    data = nearestResize(rgba, width, height, fw, fh);
    w = fw;
    h = fh;
  }
  if (w === box.width && h === box.height) return { data, width: w, height: h };
  const bottom = place.canvasHeight - box.top - box.height;
  const up = nearestAtCentres(flipRows(data, w, h), w, h, place.us, place.vs, [box.left, box.left + box.width, bottom, bottom + box.height]);
  return { data: flipRows(up, box.width, box.height), width: box.width, height: box.height };
}
