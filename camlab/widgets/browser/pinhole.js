import { formatFixed } from "./geometry.js";
import { liveImage } from "./homography.js";
import { renderPlanes } from "./textured.js";
import { project3d } from "./view3d.js";
import { dot, polygon, polyline, putPixels, textLines } from "./drawing.js";
// (one line each: esm_source drops the lines that start with "import")
// Lesson 01's pinhole_projection drawn in the browser: twin of
// camlab.widgets.pinhole_camera.pinhole_projection's update. The 3-D view (the box's seen faces and
// edges, the rays, both image planes with the faces' pictures) is camlab.plotting.optics.pinhole_view
// (its twin pinholeView here) projected as mplot3d projects it; the recorded image is rendered
// plane by plane (textured.js's renderPlanes, twin of camlab.render.render) and shown as the
// kernel's live canvas shows it (liveImage). The readout stays the kernel's.

// Twin: camlab.pinhole.project_pinhole(X, f, plane): f (X, Y) / Z on the virtual plane, its negative
// on the real one; NaN where Z <= 0.
export function projectPinhole(X, f, plane = "virtual") {
  const s = plane === "real" ? -1 : 1;
  return X.map(([x, y, z]) => (z > 0 ? [(s * f * x) / z, (s * f * y) / z] : [NaN, NaN]));
}

// Twin: camlab.plotting.optics.pinhole_camera._clip_to_frame(polygon, hw, hh): Sutherland-Hodgman.
export function clipToFrame(poly, hw, hh) {
  let points = poly.map((p) => [p[0], p[1]]);
  for (const [axis, limit] of [[0, hw], [0, -hw], [1, hh], [1, -hh]]) {
    const inside = (p) => (limit > 0 ? p[axis] <= limit : p[axis] >= limit);
    const kept = [];
    points.forEach((current, k) => {
      const previous = points[(k - 1 + points.length) % points.length];
      if (inside(current) !== inside(previous)) {
        const t = (limit - previous[axis]) / (current[axis] - previous[axis]);
        kept.push([previous[0] + t * (current[0] - previous[0]), previous[1] + t * (current[1] - previous[1])]);
      }
      if (inside(current)) kept.push(current);
    });
    points = kept;
    if (!points.length) break;
  }
  return points;
}

// Twin: numpy.round(x, digits) (half to even).
function roundTo(x, digits) {
  const k = 10 ** digits, y = x * k, r = Math.round(y);
  return (r - y === 0.5 && r % 2 !== 0 ? r - 1 : r) / k;
}

// Twin: numpy.unique(rows, axis=0): the distinct rows, sorted lexicographically.
function uniqueRows(rows) {
  const sorted = [...rows].sort((a, b) => a[0] - b[0] || a[1] - b[1] || a[2] - b[2]);
  return sorted.filter((r, i) => i === 0 || r.some((c, j) => c !== sorted[i - 1][j]));
}

// Twin: camlab.plotting.optics.pinhole_camera._unique_segments: each segment once, either way round.
function uniqueSegments(segments) {
  const seen = new Set();
  return segments.filter(([a, b]) => {
    const ends = [a, b].map((p) => p.map((c) => roundTo(c, 9) + 0)).sort((p, q) => p[0] - q[0] || p[1] - q[1] || p[2] - q[2]);
    const key = JSON.stringify(ends);
    if (seen.has(key)) return false;
    seen.add(key);
    return true;
  });
}

const sub = (a, b) => a.map((c, i) => c - b[i]);

// Twin: camlab.plotting.optics.pinhole_view(edges, fDraw, (polygons, greys), planeHalf) with faces
// given: the seen faces far to near with their greys, their edges once each, the rays from their
// corners through the pinhole to the real plane, both planes' frames and the faces' pictures cut at
// them (camera frame, metres).
export function pinholeView(polygons, greys, fDraw, planeHalf) {
  const centres = polygons.map((p) => [0, 1, 2].map((i) => p.reduce((s, q) => s + q[i], 0) / p.length));
  const seenFaces = polygons
    .map((p, k) => k)
    .sort((i, j) => centres[j][2] - centres[i][2])
    .filter((k) => {
      const p = polygons[k], a = sub(p[1], p[0]), b = sub(p[2], p[1]);
      const n = [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
      return -(n[0] * centres[k][0] + n[1] * centres[k][1] + n[2] * centres[k][2]) > 0;
    });
  const h = planeHalf;
  const box = seenFaces.map((k) => [polygons[k], greys[k]]);
  const edges = uniqueSegments(seenFaces.flatMap((k) => polygons[k].map((p, i, all) => [p, all[(i + 1) % all.length]])));
  const corners = uniqueRows(seenFaces.flatMap((k) => polygons[k].map((p) => p.map((c) => roundTo(c, 12) + 0))));
  const out = { plane_half: h, edges, frames: {}, images: {}, fills: { box } };
  for (const [name, sign] of [["real", -1], ["virtual", 1]]) {
    const z = sign * fDraw;
    out.frames[name] = [[-h, -h * 0.75, z], [h, -h * 0.75, z], [h, h * 0.75, z], [-h, h * 0.75, z], [-h, -h * 0.75, z]];
    out.images[name] = edges.map((seg) => projectPinhole(seg, fDraw, name).map(([x, y]) => [x, y, z]));
    out.fills[name] = box
      .map(([p, grey]) => [clipToFrame(projectPinhole(p, fDraw, name), h, 0.75 * h), grey])
      .filter(([p]) => p.length >= 3)
      .map(([p, grey]) => [p.map(([x, y]) => [x, y, z]), grey]);
  }
  out.rays = corners.map((c) => [c, c.map((x) => (-x * fDraw) / c[2])]);
  return out;
}

// Twin: camlab.widgets.pinhole_camera.plane_distance(f, nearest): where the 3-D view draws the planes.
export function planeDistance(f, nearest, { planeScale, planeRoom, planeMax }) {
  return Math.min(planeScale * f, planeRoom * nearest, planeMax);
}

// Twin: camlab.widgets.pinhole_camera._bar_ends(u_min, u_max, width): the width bar clipped to the
// image and the end marks that fall inside it.
export function barEnds(uMin, uMax, width) {
  const lo = -0.5, hi = width - 0.5;
  return { bar: [Math.max(uMin, lo), Math.min(uMax, hi)], ends: [uMin, uMax].filter((u) => lo <= u && u <= hi) };
}

// Twin: the numbers of pinhole_projection's update (its state: K, fx, box_width_px, fov_deg,
// f_draw, draw_scale, bar_clipped, plane), its 3-D view (pinholeView), the bar and the two texts,
// at the sliders' values p {focal_mm, distance, real_plane}. `scene` holds the box's faces at
// distance scene.boxDistance (camera frame), their greys, the sensor and the plane-placing constants.
export function pinholeFrame(scene, p) {
  const f = p.focal_mm * 1e-3, Z = p.distance, real = Boolean(p.real_plane);
  const [w, h] = scene.size;
  const dz = Z - scene.boxDistance;
  const polygons = scene.faces.map((face) => face.map(([x, y, z]) => [x, y, z + dz]));
  const corners = polygons.flat();
  const fDraw = planeDistance(f, Math.min(...corners.map((c) => c[2])), scene);
  const scale = fDraw / f;
  const view = pinholeView(polygons, scene.greys, fDraw, (scale * scene.sensor[0]) / 2);
  const fx = f / scene.pitch;
  const K = [[fx, 0, (w - 1) / 2], [0, fx, (h - 1) / 2], [0, 0, 1]];
  let u = corners.map(([x, , z]) => (K[0][0] * x) / z + K[0][2]);
  if (real) u = u.map((x) => w - 1 - x);
  const uMin = Math.min(...u), uMax = Math.max(...u);
  const span = uMax - uMin;
  const fov = (2 * Math.atan(scene.sensor[0] / (2 * f)) * 180) / Math.PI;
  const title = (real ? "real image (rotated 180 deg)" : "virtual image (upright)") + `\nfield of view ${formatFixed(fov, 1)} deg; box ${formatFixed(span, 0)} px wide`;
  const s = formatFixed(scale, 1);
  const note = `image planes at ${s} f from the pinhole (black dot), their sensor frames ${s} x enlarged`;
  const { bar, ends } = barEnds(uMin, uMax, w);
  return { K, fx, fov_deg: fov, box_width_px: span, f_draw: fDraw, draw_scale: scale, bar, ends, bar_clipped: ends.length < 2, plane: real ? "real" : "virtual", view, title, note, dz };
}

// Twin: matplotlib's mplot3d projection then the axes' data-to-canvas map: a camera-frame point
// (x right, y down, z forward) drawn at plot (z, -x, -y), projected by the axes' 4x4 M
// (proj3d.proj_transform) and mapped by `toPixels` (to_canvas_pixels). Returns [u, v, depth]:
// canvas px and the projected depth mplot3d sorts a collection's polygons by.
export function pinholePixels(M, toPixels, [x, y, z]) {
  const [[px, py, depth]] = project3d(M, [[z, -x, -y]]);
  const T = toPixels;
  return [T[0][0] * px + T[0][1] * py + T[0][2], T[1][0] * px + T[1][1] * py + T[1][2], depth];
}

// A Poly3DCollection as mplot3d draws it: each polygon projected, the farthest (largest mean
// projected depth) first.
function fills3d(ctx, scene, polys) {
  const projected = polys.map(([p, grey]) => {
    const pts = p.map((c) => pinholePixels(scene.M, scene.toPixels, c));
    return [pts, pts.reduce((s, c) => s + c[2], 0) / pts.length, grey];
  });
  projected.sort((a, b) => b[1] - a[1]);
  for (const [pts, , grey] of projected) {
    const g = Math.round(grey * 255);
    polygon(ctx, pts, { fill: `rgb(${g}, ${g}, ${g})` });
  }
}

// Segments (camera frame) as one canvas polyline with a break after each.
function segments3d(scene, segs) {
  return segs.flatMap(([a, b]) => [pinholePixels(scene.M, scene.toPixels, a), pinholePixels(scene.M, scene.toPixels, b), [NaN, NaN]]);
}

const PINHOLE_WORK = new WeakMap(); // per scene: the planes' texture levels, the render's buffers, RGBA images

// The render's planes and texture levels from the scene: the box's faces (float32 textures,
// base64) and the wall (its squares, each `texels` texels wide: numpy.kron, as fixtures builds it).
function pinholeWork(scene) {
  let work = PINHOLE_WORK.get(scene);
  if (!work) {
    const levels = scene.planes.map((p) => {
      const t = p.texture;
      const bytes = Uint8Array.from(atob(t.data), (c) => c.charCodeAt(0));
      let data = new Float32Array(bytes.buffer);
      let width = t.width, height = t.height;
      if (t.texels) { // a texture of flat squares, each texels x texels
        const n = t.texels, small = data;
        width *= n;
        height *= n;
        data = new Float32Array(width * height);
        for (let r = 0; r < height; r++) for (let c = 0; c < width; c++) data[r * width + c] = small[Math.floor(r / n) * t.width + Math.floor(c / n)];
      }
      return [{ data, width, height }];
    });
    work = { levels, render: {}, panels: {}, rgba: {} };
    PINHOLE_WORK.set(scene, work);
  }
  return work;
}

// The grey image through matplotlib's "gray" colormap (scene.lut: its 256 levels, as to_rgba(bytes=True)
// gives them), RGBA; `flip` turns it by 180 degrees (img[::-1, ::-1]).
function greyRGBA(img, lut, out, flip) {
  const n = img.length;
  for (let i = 0; i < n; i++) {
    const x = img[flip ? n - 1 - i : i] * 256;
    const g = lut[Math.min(255, Math.max(0, Math.floor(x)))];
    out[4 * i] = g;
    out[4 * i + 1] = g;
    out[4 * i + 2] = g;
    out[4 * i + 3] = 255;
  }
  return out;
}

// Twin: camlab.render.render(fixtures.box_before_wall(Z), K, size).irradiance: the recorded image
// at a frame's K and box distance, (h x w) float32 rows.
export function pinholeImage(scene, frame) {
  const work = pinholeWork(scene);
  const planes = scene.planes.map((pl) => (pl.box ? { ...pl, t: [pl.t[0], pl.t[1], pl.t[2] + frame.dz] } : pl));
  return renderPlanes(planes, work.levels, frame.K, scene.size, scene.supersample, scene.irradianceWhereEmpty, work.render);
}

export function drawPinhole(ctx, scene, p) {
  const frame = pinholeFrame(scene, p);
  const work = pinholeWork(scene);
  const v = frame.view, st = scene.styles;
  // the 3-D view, in its fixed order (zorder): box fills, edges, rays, virtual plane, pinhole, real plane
  fills3d(ctx, scene, v.fills.box);
  polyline(ctx, segments3d(scene, v.edges), st.box);
  polyline(ctx, segments3d(scene, v.rays), st.rays);
  for (const name of ["virtual", "pinhole", "real"]) {
    if (name === "pinhole") {
      dot(ctx, pinholePixels(scene.M, scene.toPixels, [0, 0, 0]), st.pinhole);
      continue;
    }
    fills3d(ctx, scene, v.fills[name]);
    polyline(ctx, v.frames[name].map((c) => pinholePixels(scene.M, scene.toPixels, c)), st.frames[name]);
  }
  // the recorded image and the two planes' pictures
  const [w, h] = scene.size;
  const img = pinholeImage(scene, frame);
  const rgba = (key, flip) => greyRGBA(img, scene.lut, (work.rgba[key] ||= new Uint8ClampedArray(w * h * 4)), flip);
  const pictures = { virtual: rgba("virtual", false), real: rgba("real", true) };
  const shown = { image: pictures[frame.plane], virtual: pictures.virtual, real: pictures.real };
  for (const panel of scene.panels) {
    const out = liveImage(shown[panel.image], w, h, panel.place);
    putPixels(ctx, (work.panels[panel.image] ||= {}), out.data, out.width, out.height, panel.place.box);
    if (panel.image === "image") {
      const T = scene.imageToPixels, at = ([x, y]) => [T[0][0] * x + T[0][1] * y + T[0][2], T[1][0] * x + T[1][1] * y + T[1][2]];
      const vBar = scene.barRow;
      polyline(ctx, frame.bar.map((u) => at([u, vBar])), st.bar);
      for (const u of frame.ends) { // the "|" marks, centred in the pixel Agg stamps them in
        const [x, y] = at([u, vBar]).map((c) => Math.floor(c + 0.5) + 0.5);
        polyline(ctx, [[x, y - st.end.size / 2], [x, y + st.end.size / 2]], st.end);
      }
    }
    for (const spine of panel.spines) polyline(ctx, spine.points, spine.style);
    if (panel.image === "image") {
      textLines(ctx, frame.title, st.title);
      textLines(ctx, frame.note, st.note);
    }
  }
  return frame;
}
