import { cross, unit } from "./geometry.js";
// (one line: esm_source drops the lines that start with "import")
// A matplotlib 3-D axes (mpl_toolkits.mplot3d) in the browser: its projection and camlab's fit of
// its limits, for a demo whose 3-D view turns or refits on every move (lesson 04's camera_explorer
// and opencv_vs_opengl). Twins: mplot3d's Axes3D.get_proj and proj3d (matplotlib 3.10-3.11, the
// vertical axis z, no roll, the default perspective: focal length 1 at distance 10) and
// camlab.plotting.view3d.fit_view; tests/test_browser_camera_parity.py runs them against both.

const DEGREES = Math.PI / 180;
// Axes3D.set_box_aspect's scale (tuned to matplotlib 3.2's look, times 25/24 for 3.9's margins).
const BOX_SCALE = 1.8294640721620434 * 25 / 24;
const EYE_DISTANCE = 10; // Axes3D._dist

function matmul4(a, b) {
  return a.map((row) => b[0].map((_, j) => row.reduce((s, v, k) => s + v * b[k][j], 0)));
}

// Twin: Axes3D.set_box_aspect(aspect, zoom=zoom)'s box: the aspect scaled to BOX_SCALE * zoom long.
function boxAspect(aspect, zoom) {
  const k = (BOX_SCALE * zoom) / Math.hypot(...aspect);
  return aspect.map((a) => a * k);
}

// Twin: Axes3D.get_proj() with limits `lims` ([[x0, x1], [y0, y1], [z0, z1]], m), box aspect
// `aspect` zoomed by `zoom`, and the view (elev, azim) in degrees: the 4 x 4 map from world to the
// axes' projected coordinates (proj3d.proj_transform divides by its last row).
export function axesProjection(lims, aspect, zoom, elev, azim) {
  const box = boxAspect(aspect, zoom);
  const d = lims.map(([lo, hi], i) => (hi - lo) / box[i]);
  const worldM = [
    [1 / d[0], 0, 0, -lims[0][0] / d[0]],
    [0, 1 / d[1], 0, -lims[1][0] / d[1]],
    [0, 0, 1 / d[2], -lims[2][0] / d[2]],
    [0, 0, 0, 1],
  ];
  const R = box.map((b) => 0.5 * b);
  const e = elev * DEGREES, a = azim * DEGREES;
  const ps = [Math.cos(e) * Math.cos(a), Math.cos(e) * Math.sin(a), Math.sin(e)];
  const eye = R.map((r, i) => r + EYE_DISTANCE * ps[i]);
  const normElev = ((elev + 360) % 360) > 180 ? ((elev + 360) % 360) - 360 : (elev + 360) % 360;
  const V = [0, 0, Math.abs(normElev * DEGREES) > Math.PI / 2 ? -1 : 1];
  const w = unit(eye.map((c, i) => c - R[i]));
  const u = unit(cross(V, w));
  const v = cross(w, u);
  const dotE = (x) => -(x[0] * eye[0] + x[1] * eye[1] + x[2] * eye[2]);
  const viewM = [[...u, dotE(u)], [...v, dotE(v)], [...w, dotE(w)], [0, 0, 0, 1]];
  const [zf, zb] = [-EYE_DISTANCE, EYE_DISTANCE];
  const projM = [
    [1, 0, 0, 0],
    [0, 1, 0, 0],
    [0, 0, (zf + zb) / (zf - zb), (-2 * (zf * zb)) / (zf - zb)],
    [0, 0, -1, 0],
  ];
  return matmul4(projM, matmul4(viewM, worldM));
}

// Twin: proj3d.proj_transform(xs, ys, zs, M): world points (rows) to projected [x, y, z].
export function project3d(M, points) {
  return points.map((p) => {
    const h = M.map((row) => row[0] * p[0] + row[1] * p[1] + row[2] * p[2] + row[3]);
    return [h[0] / h[3], h[1] / h[3], h[2] / h[3]];
  });
}

// Twin: what art3d.Line3D.draw hands its 2-D line: the projected (x, y), NaN where
// proj3d._proj_transform_vec_clip masks a point (outside -1..1 across, or behind the eye).
export function lineOnScreen(M, points) {
  return project3d(M, points).map(([x, y, z]) =>
    x >= -1 && x <= 1 && y >= -1 && y <= 1 && z <= 0 ? [x, y] : [NaN, NaN],
  );
}

// Twin: camlab.plotting.view3d.fit_view(ax, points, fill, max_zoom) on an axes at (elev, azim)
// whose 2-D view box is `viewBox` ([x0, y0, x1, y1]: Axes3D's viewLim): equal-aspect limits about
// the points, shifted across the line of sight until their picture is centred and zoomed until it
// spans `fill` of the box. Returns {lims, zoom, M}.
export function fitView(points, elev, azim, viewBox, fill = 0.92, maxZoom = 3.0) {
  const pts = points.filter((p) => p.every(Number.isFinite));
  const lo = [0, 1, 2].map((i) => Math.min(...pts.map((p) => p[i])));
  const hi = [0, 1, 2].map((i) => Math.max(...pts.map((p) => p[i])));
  const mid = lo.map((l, i) => (l + hi[i]) / 2);
  // set_equal_aspect(ax, pts, zoom=1): a cube 2% larger than the points' largest extent
  const cube = Math.max(Math.max(...hi.map((h, i) => h - lo[i])) / 2, 1e-6) * (1 + 0.02);
  const lim = mid.map((c) => [c - cube, c + cube]);
  const half = lim.map(([l, h]) => (h - l) / 2);
  const target = [(viewBox[0] + viewBox[2]) / 2, (viewBox[1] + viewBox[3]) / 2];
  const aspect = [1, 1, 1];
  const limits = (centre) => centre.map((c, i) => [c - half[i], c + half[i]]);
  const picture = (centre, zoom) => {
    const xy = project3d(axesProjection(limits(centre), aspect, zoom, elev, azim), pts);
    const xs = xy.map((p) => p[0]), ys = xy.map((p) => p[1]);
    return [[Math.min(...xs), Math.min(...ys)], [Math.max(...xs), Math.max(...ys)]];
  };
  const az = azim * DEGREES, el = elev * DEGREES;
  const across = [
    [-Math.sin(az), Math.cos(az), 0],
    [-Math.cos(az) * Math.sin(el), -Math.sin(az) * Math.sin(el), Math.cos(el)],
  ];
  let centre = lim.map(([l, h]) => (l + h) / 2);
  let zoom = 1.0;
  for (let k = 0; k < 3; k++) {
    let [a, b] = picture(centre, zoom);
    const now = [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2];
    const offset = [now[0] - target[0], now[1] - target[1]];
    const step = 1e-3 * Math.max(...half);
    const jac = across.map((d) => {
      const [a2, b2] = picture(centre.map((c, i) => c + step * d[i]), zoom);
      return [((a2[0] + b2[0]) / 2 - now[0]) / step, ((a2[1] + b2[1]) / 2 - now[1]) / step];
    }); // jac[j] is column j
    const det = jac[0][0] * jac[1][1] - jac[1][0] * jac[0][1];
    const s0 = (offset[0] * jac[1][1] - jac[1][0] * offset[1]) / det;
    const s1 = (jac[0][0] * offset[1] - offset[0] * jac[0][1]) / det;
    centre = centre.map((c, i) => c - (across[0][i] * s0 + across[1][i] * s1));
    [a, b] = picture(centre, zoom);
    const span = Math.max(b[0] - a[0], b[1] - a[1]);
    zoom = Math.min(Math.max((zoom * fill * (viewBox[2] - viewBox[0])) / Math.max(span, 1e-12), 0.2), maxZoom);
  }
  const lims = limits(centre);
  return { lims, zoom, M: axesProjection(lims, aspect, zoom, elev, azim) };
}
