// The per-move arithmetic of the browser-drawn demos, in plain JavaScript (no build step).
//
// Every function here has a numpy twin in camlab, named beside it, and
// tests/test_browser_geometry_parity.py runs both on random inputs under node and compares them
// (1e-9 relative). Conventions are camlab's (docs/conventions.md): points are rows, pixels are
// (u, v) with v down, X_cam = R X + t, P = K [R | t]; NaN where a point has no Euclidean position.
// Matrices are arrays of rows; a point list is an array of [x, y] (or [x, y, z]) rows.

// Twin: a @ b (numpy).
export function matmul(a, b) {
  const n = a.length, m = b[0].length, k = b.length;
  const out = [];
  for (let i = 0; i < n; i++) {
    const row = new Array(m).fill(0);
    for (let j = 0; j < m; j++) {
      let s = 0;
      for (let r = 0; r < k; r++) s += a[i][r] * b[r][j];
      row[j] = s;
    }
    out.push(row);
  }
  return out;
}

// Twin: camlab.camera.Camera(K, R, t).P, the 3x4 matrix K [R | t].
export function composeP(K, R, t) {
  return matmul(K, R.map((row, i) => [row[0], row[1], row[2], t[i]]));
}

function det3(M) {
  return (
    M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1]) -
    M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0]) +
    M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0])
  );
}

// Twin: camlab.camera.project_points(P, X): pixels of world points, NaN behind a finite camera
// (sign(det M) w <= 0, M = P's left 3x3) or at infinity (w = 0).
export function projectPoints(P, X) {
  let scale = 0;
  for (const row of P) for (const v of row) scale = Math.max(scale, Math.abs(v));
  const det = det3(P);
  const finite = Math.abs(det) > 1e-12 * scale ** 3;
  return X.map(([x, y, z]) => {
    const h = P.map((r) => r[0] * x + r[1] * y + r[2] * z + r[3]);
    const w = h[2];
    const behind = finite ? Math.sign(det) * w <= 0 : w === 0;
    return behind ? [NaN, NaN] : [h[0] / w, h[1] / w];
  });
}

// Twin: numpy.cross for 3-vectors.
export function cross(a, b) {
  return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
}

function homogeneous(p) {
  return p.length === 2 ? [p[0], p[1], 1] : p;
}

// Twin: camlab.projective.join(p, q): the line p x q through two (Euclidean or homogeneous) points.
export function join(p, q) {
  return cross(homogeneous(p), homogeneous(q));
}

// Twin: camlab.projective.meet(l, m): the point l x m where two lines cross (ideal if parallel).
export function meet(l, m) {
  return cross(l, m);
}

// Twin: camlab.projective.from_homogeneous: divide by w; NaN where w is exactly 0.
export function fromHomogeneous(h) {
  const w = h[h.length - 1];
  return h.slice(0, -1).map((c) => (w === 0 ? NaN : c / w));
}

// Twin: camlab.projective.map_points(H, points) for Euclidean (N, 2) rows: x' ~ H x.
export function mapPoints(H, points) {
  return points.map(([x, y]) => fromHomogeneous(H.map((r) => r[0] * x + r[1] * y + r[2])));
}

// Twin: camlab.widgets.start_here.turn_and_scale(angle_deg, s): the 3x3 map of x' = s R(angle) x.
export function turnAndScale(angleDeg, s) {
  const t = (angleDeg * Math.PI) / 180;
  const c = Math.cos(t), n = Math.sin(t);
  return [[s * c, -s * n, 0], [s * n, s * c, 0], [0, 0, 1]];
}

// Twin: camlab.widgets.start_here.turn_path(angle_deg, scale, start, samples): the arc of the
// turn R(t angle) x0 for t in [0, 1] (samples points), then the scaled end point s R(angle) x0.
export function turnPath(angleDeg, scale, start, samples = 61) {
  const [x, y] = start;
  const out = [];
  for (let i = 0; i < samples; i++) {
    const t = samples === 1 ? 0 : i / (samples - 1);
    const th = ((angleDeg * Math.PI) / 180) * t;
    out.push([x * Math.cos(th) - y * Math.sin(th), x * Math.sin(th) + y * Math.cos(th)]);
  }
  const end = out[out.length - 1];
  out.push([scale * end[0], scale * end[1]]);
  return out;
}

// Twin: camlab.widgets.start_here.turn_way(angle_deg, samples, scale), radius = WAY_RADIUS * scale: the arc of the arrow that shows the
// way of the turn, sweepDeg about (0, 1) on the circle of `radius`, the way of the angle's sign; [] at 0.
export function turnWay(angleDeg, radius, sweepDeg, samples = 25) {
  if (angleDeg === 0) return [];
  const out = [];
  for (let i = 0; i < samples; i++) {
    const t = samples === 1 ? 0 : i / (samples - 1) - 0.5;
    const phi = ((90 + Math.sign(angleDeg) * sweepDeg * t) * Math.PI) / 180;
    out.push([radius * Math.cos(phi), radius * Math.sin(phi)]);
  }
  return out;
}

// Twin: camlab.widgets.start_here.arrowhead_size(angle_deg, radius): marker size in points, [7, 15].
export function arrowheadSize(angleDeg, radius = 1.4) {
  const arc = Math.abs((angleDeg * Math.PI) / 180) * radius;
  return Math.min(15, Math.max(7, (15 * arc) / 0.98));
}

// Twin: Python's format(x, f".{digits}f"). toFixed picks the decimal nearest the double, as Python
// does, but rounds an exact tie away from zero where Python rounds half to even: a tie at `digits`
// decimals is a double x with x 2^(digits+1) odd (x 10^digits = m 5^digits / 2), fixed here. -0 keeps
// its sign, as in Python.
export function formatFixed(x, digits) {
  let r = x.toFixed(digits);
  if (Number.isInteger(x * 2 ** (digits + 1)) && !Number.isInteger(x * 2 ** digits)) {
    const n = x * 10 ** digits; // exact: m 5^digits / 2
    const f = Math.floor(n);
    r = ((f % 2 === 0 ? f : f + 1) / 10 ** digits).toFixed(digits);
  }
  if (Object.is(x, -0) || (x < 0 && !r.startsWith("-"))) r = `-${r}`;
  return r;
}

function roundsToZero(text) {
  return /^-?0(\.0*)?$/.test(text);
}

// Twin: camlab.widgets.start_here.tip_readout's numbers: format(round(c, 2) + 0.0, "+.2f").
export function fixed2(c) {
  const r = formatFixed(c, 2);
  if (roundsToZero(r)) return "+0.00";
  return r.startsWith("-") ? r : `+${r}`;
}

// Twin: camlab.widgets.start_here.tip_readout(point): "(+x.xx, -y.yy)".
export function tipReadout([x, y]) {
  return `(${fixed2(x)}, ${fixed2(y)})`;
}

// Twin: camlab.plotting.optics.similar_triangles._signed (and camlab.widgets.pinhole_camera._signed):
// the value with its sign, and a plain "0.0" where it rounds to zero.
export function signed(x, digits) {
  const r = formatFixed(x, digits);
  if (roundsToZero(r)) return (0).toFixed(digits);
  return r.startsWith("-") ? r : `+${r}`;
}

// Twin: camlab.plotting.optics.similar_triangles._dimension_layout.
function dimensionLayout(a, b, text, { offset = [0, 0], ha = "center", va = "center", labelAt = null, minArrow = 0 } = {}) {
  const at = labelAt !== null ? labelAt : [(a[0] + b[0]) / 2 + offset[0], (a[1] + b[1]) / 2 + offset[1]];
  const shown = Math.hypot(b[0] - a[0], b[1] - a[1]) >= minArrow;
  return { a, b, shown, text, at, ha, va };
}

// Twin: camlab.plotting.optics.similar_triangles_layout(f, Z, Y, h): the side view's moving parts in
// (z, -y) plot coordinates and their labels; `rooms` carries its constants (SHORTEST_ARROW,
// F_LABEL_ROOM, Z_LABEL_ROOM) as {shortest, fRoom, zRoom}.
export function similarTrianglesLayout(f, Z, Y, h, rooms) {
  const y = (f * Y) / Z;
  const up = -Y, upImg = -y;
  const away = up >= 0 ? -0.12 * h : 0.12 * h;
  const inside = Z >= rooms.zRoom;
  const fInside = f >= rooms.fRoom;
  const lift = Math.abs(up) >= 0.3 ? 0.0 : (away < 0 ? 0.15 : -0.15) - up / 2;
  const short = rooms.shortest;
  const dims = {
    Z: dimensionLayout([0, 3 * away], [Z, 3 * away], `Z = ${formatFixed(Z, 2)} m`, {
      ha: inside ? "center" : "left",
      labelAt: inside ? null : [Z + 0.08, 3 * away],
    }),
    f: dimensionLayout([0, away], [f, away], `f = ${formatFixed(f, 2)} m`, {
      offset: [0, away],
      ha: fInside ? "center" : "left",
      labelAt: fInside ? null : [f + 0.06, away],
    }),
    Y: dimensionLayout([Z + 0.1, 0], [Z + 0.1, up], ` Y = ${signed(Y, 2)} m`, {
      offset: [0.05, lift],
      ha: "left",
      minArrow: short,
    }),
    y: dimensionLayout([f + 0.06, 0], [f + 0.06, upImg], `virtual: y = ${signed(y * 100, 1)} cm`, {
      va: "bottom",
      labelAt: [f, h + 0.02],
      minArrow: short,
    }),
    y_real: dimensionLayout([-f - 0.06, 0], [-f - 0.06, -upImg], `real: ${signed(-y * 100, 1)} cm`, {
      va: "top",
      labelAt: [-f, -h - 0.02],
      minArrow: short,
    }),
  };
  return {
    y,
    big: [[0, 0], [Z, 0], [Z, up]],
    small: [[0, 0], [f, 0], [f, upImg]],
    object: [[Z, 0], [Z, up]],
    point: [Z, up],
    ray: [[-f, y], [Z, up]],
    planes: [[-f, -h], [-f, h], [NaN, NaN], [f, -h], [f, h]],
    virtual: [[f, 0], [f, upImg]],
    real: [[-f, 0], [-f, y]],
    pinhole: [0, 4.6 * away],
    dims,
  };
}

// Twin: camlab.widgets.pinhole_camera.ratios_title(f, Z, Y): the two ratios over similar_triangles.
export function ratiosTitle(f, Z, Y) {
  const y = (f * Y) / Z;
  return (
    `y / f = ${signed(y * 100, 1)} cm / ${formatFixed(f * 100, 0)} cm = ${signed(y / f, 3)}   and   ` +
    `Y / Z = ${signed(Y, 2)} m / ${formatFixed(Z, 2)} m = ${signed(Y / Z, 3)}\n` +
    "click or drag in the figure to move the object point"
  );
}

// ---- lesson 05: the dolly zoom camera and its affine approximations ----------------------------

export function dot3(a, b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

export function unit(v) {
  const n = Math.hypot(v[0], v[1], v[2]);
  return v.map((c) => c / n);
}

// Twin: camlab.camera.orbit_eye(azimuth, elevation, distance, target): radians, metres.
export function orbitEye(azimuth, elevation, distance, target) {
  const ce = Math.cos(elevation);
  return [
    target[0] + distance * ce * Math.cos(azimuth),
    target[1] + distance * ce * Math.sin(azimuth),
    target[2] + distance * Math.sin(elevation),
  ];
}

// Twin: camlab.camera.look_at_rotation(eye, target, up) (what Camera.look_at uses): R (cam_from_world), rows the camera's x, y, z axes.
export function lookAt(eye, target, up = [0, 0, 1]) {
  const z = unit([target[0] - eye[0], target[1] - eye[1], target[2] - eye[2]]);
  const x = unit(cross(z, up));
  return [x, cross(z, x), z];
}

// Twin: camlab.affine.dolly_zoom_camera(distance, azimuth, elevation, target, f0, d0,
// principal_point, image_offset): {K, R, t}, focal f0 d / d0, the target at depth d.
export function dollyZoomCamera(distance, azimuth, elevation, target, f0, d0, principalPoint, imageOffset = 0) {
  const f = (f0 * distance) / d0;
  const R = lookAt(orbitEye(azimuth, elevation, distance, target), target);
  const shift = (imageOffset * d0) / f0;
  const centre = target.map((c, i) => c - shift * R[0][i] - distance * R[2][i]);
  const K = [[f, 0, principalPoint[0]], [0, f, principalPoint[1]], [0, 0, 1]];
  return { K, R, t: R.map((row) => -dot3(row, centre)) };
}

// Twin: camlab.camera.Camera(K, R, t).project(X) without distortion: NaN where z_cam <= 0.
export function cameraProject(cam, X) {
  const { K, R, t } = cam;
  return X.map((p) => {
    const c = R.map((row, i) => dot3(row, p) + t[i]);
    if (!(c[2] > 0)) return [NaN, NaN];
    const x = c[0] / c[2], y = c[1] / c[2];
    return [K[0][0] * x + K[0][1] * y + K[0][2], K[1][0] * x + K[1][1] * y + K[1][2]];
  });
}

// Twin: camlab.affine.affine_approximation(camera, X0): K [r1 t1; r2 t2; 0 d0] / d0, d0 = X0's depth.
export function affineApproximation(cam, X0) {
  const { K, R, t } = cam;
  const d0 = dot3(R[2], X0) + t[2];
  const E = [[...R[0], t[0]], [...R[1], t[1]], [0, 0, 0, d0]];
  return matmul(K, E).map((row) => row.map((v) => v / d0));
}

// Twin: camlab.affine.orthographic_matrix(R, t): keep the camera x, y (metres), forget depth.
export function orthographicMatrix(R, t) {
  return [[...R[0], t[0]], [...R[1], t[1]], [0, 0, 0, 1]];
}

function signedDepths(camOrP, points) {
  if (!Array.isArray(camOrP)) return points.map((p) => dot3(camOrP.R[2], p) + camOrP.t[2]);
  const P = camOrP;
  let scale = 0;
  for (const row of P) for (const v of row) scale = Math.max(scale, Math.abs(v));
  const det = det3(P);
  if (Math.abs(det) <= 1e-12 * scale ** 3) return points.map(() => 1);
  return points.map((p) => Math.sign(det) * (dot3(P[2], p) + P[2][3]));
}

// Twin: camlab.camera.project_segments(camera, segments): (M, 2, 3) world segments to (M, 2, 2)
// pixels, a half-visible segment clipped at 1/1000 of its front end's depth first; `camOrP` is a
// camera {K, R, t} or a 3x4 P.
export function projectSegments(camOrP, segments, near = 1e-3) {
  const clipped = segments.map((seg) => {
    const [za, zb] = signedDepths(camOrP, seg);
    const out = [seg[0], seg[1]];
    for (const [behind, front, zBehind, zFront] of [[0, 1, za, zb], [1, 0, zb, za]]) {
      if (zBehind <= 0 && zFront > 0) {
        const s = ((1 - near) * zFront) / (zFront - zBehind);
        out[behind] = seg[front].map((c, i) => c + s * (seg[behind][i] - c));
      }
    }
    return out;
  });
  const flat = clipped.flat();
  const uv = Array.isArray(camOrP) ? projectPoints(camOrP, flat) : cameraProject(camOrP, flat);
  return clipped.map((_, i) => [uv[2 * i], uv[2 * i + 1]]);
}

// Twin: camlab.affine.matched_points_in_frame(camera, P_affine, segments, size, samples): the two
// images of `samples` points along each segment, where both fall inside the (width, height) frame.
export function matchedPointsInFrame(cam, PAffine, segments, size, samples) {
  const X = [];
  for (const [a, b] of segments) {
    for (let k = 0; k < samples; k++) {
      const s = samples === 1 ? 0 : k / (samples - 1);
      X.push(a.map((c, i) => c + s * (b[i] - c)));
    }
  }
  const pa = cameraProject(cam, X), pb = projectPoints(PAffine, X);
  const [w, h] = size;
  const inFrame = ([u, v]) => u >= -0.5 && u <= w - 0.5 && v >= -0.5 && v <= h - 0.5;
  const keep = pa.map((p, i) => inFrame(p) && inFrame(pb[i]));
  return { perspective: pa.filter((_, i) => keep[i]), affine: pb.filter((_, i) => keep[i]) };
}

// Twin: camlab.plotting.wireframes.polyline_data for 2-D segments: start, end and a NaN row each.
export function polylineData(segments) {
  return segments.flatMap((seg) => [seg[0], seg[1], [NaN, NaN]]);
}

// Twin: camlab.affine.paraperspective_approximation(camera, X0): perspective linearised at X0,
// K [r1 - a r3, t1 - a (t3 - d0); r2 - b r3, t2 - b (t3 - d0); 0, d0] / d0 with (a, b) X0's
// normalised image position.
export function paraperspectiveApproximation(cam, X0) {
  const { K, R, t } = cam;
  const d0 = dot3(R[2], X0) + t[2];
  const ab = [0, 1].map((i) => (dot3(R[i], X0) + t[i]) / d0);
  const E = [0, 1].map((i) => [...R[i].map((r, j) => r - ab[i] * R[2][j]), t[i] - ab[i] * (t[2] - d0)]);
  E.push([0, 0, 0, d0]);
  return matmul(K, E).map((row) => row.map((v) => v / d0));
}

// Twin: camlab.affine.weak_perspective_error(camera, X, X0, approximation): each point's pixel
// distance between its perspective image and its image by approximation(cam, X0): a twin above, or
// its name in APPROXIMATIONS.
export function approximationError(cam, X, X0, approximation) {
  const approximate = typeof approximation === "string" ? APPROXIMATIONS[approximation] : approximation;
  const PA = approximate(cam, X0);
  const a = cameraProject(cam, X), b = projectPoints(PA, X);
  return a.map((p, i) => Math.hypot(p[0] - b[i][0], p[1] - b[i][1]));
}

// Twin: camlab.affine.dolly_zoom_errors(X, distances, azimuth, elevation, target, f0, d0,
// approximation, image_offset): the RMS of approximationError at each distance, pixels.
export function dollyZoomErrors(X, distances, azimuth, elevation, target, f0, d0, approximation, imageOffset, principalPoint) {
  return distances.map((d) => {
    const cam = dollyZoomCamera(d, azimuth, elevation, target, f0, d0, principalPoint, imageOffset);
    const e = approximationError(cam, X, target, approximation);
    return Math.sqrt(e.reduce((s, v) => s + v * v, 0) / e.length);
  });
}

// The affine approximations by the names lesson 05 gives them (camlab.widgets.affine_cameras.APPROXIMATIONS).
export const APPROXIMATIONS = {
  "weak perspective": affineApproximation,
  "para-perspective": paraperspectiveApproximation,
};

// Twin: camlab.widgets.affine_cameras.views._rms_text(rms): to 0.1 px, below 1 px to 0.01 px.
export function rmsText(rms) {
  return rms >= 0.995 ? `RMS ${formatFixed(rms, 1)} px` : `RMS ${formatFixed(rms, 2)} px`;
}

// ---- lesson 06: the projective plane -------------------------------------------------------------

// Twin: camlab.projective.clip_line(line, xlim, ylim): the two crossings, farthest apart, of the line
// with the box's edges (within 1e-9 of its span); both rows NaN when it misses the box.
export function clipLine(line, xlim, ylim) {
  const [x0, x1] = xlim, [y0, y1] = ylim;
  const eps = 1e-9 * Math.max(x1 - x0, y1 - y0);
  const pts = [[1, 0, -x0], [1, 0, -x1], [0, 1, -y0], [0, 1, -y1]]
    .map((edge) => fromHomogeneous(cross(line, edge)))
    .filter(([x, y]) => Number.isFinite(x) && Number.isFinite(y) && x >= x0 - eps && x <= x1 + eps && y >= y0 - eps && y <= y1 + eps);
  const none = [[NaN, NaN], [NaN, NaN]];
  if (pts.length < 2) return none;
  let best = -1, pair = [0, 0];
  pts.forEach((a, i) => pts.forEach((b, j) => {
    const d = Math.hypot(a[0] - b[0], a[1] - b[1]);
    if (d > best) [best, pair] = [d, [i, j]];
  }));
  if (best <= eps) return none;
  return pair.map((i) => pts[i].map((c) => c + 0)); // + 0 turns -0 into 0, as numpy's + 0.0
}

// Twin: camlab.plotting.plane.arrow_placement(point_h, xlim, ylim, anchor): {position, direction}:
// the point where it is, or an arrow's tip at 90 % of the box's half-extent from its centre,
// pointing from `anchor` (the centre when null) towards the point (an ideal point: along (x, y)).
export function arrowPlacement(pointH, xlim, ylim, anchor = null) {
  const [x, y, w] = pointH;
  const [x0, x1] = xlim, y0 = Math.min(...ylim), y1 = Math.max(...ylim);
  const centre = [(x0 + x1) / 2, (y0 + y1) / 2];
  const start = anchor === null ? centre : anchor;
  let dir;
  if (w !== 0) {
    const p = [x / w, y / w];
    if (x0 <= p[0] && p[0] <= x1 && y0 <= p[1] && p[1] <= y1) return { position: p, direction: [0, 0] };
    dir = [p[0] - start[0], p[1] - start[1]];
  } else {
    dir = [x, y];
    if (anchor !== null && dir[0] * (start[0] - centre[0]) + dir[1] * (start[1] - centre[1]) < 0) dir = [-x, -y];
  }
  const n = Math.hypot(dir[0], dir[1]);
  dir = [dir[0] / n, dir[1] / n];
  const half = [((x1 - x0) / 2) * 0.9, ((y1 - y0) / 2) * 0.9];
  let s = Infinity;
  for (const k of [0, 1]) {
    if (Math.abs(dir[k]) <= 1e-12) continue;
    s = Math.min(s, ((dir[k] > 0 ? centre[k] + half[k] : centre[k] - half[k]) - start[k]) / dir[k]);
  }
  s = Math.max(0, s);
  return { position: [start[0] + s * dir[0], start[1] + s * dir[1]], direction: dir };
}

// Twin: camlab.widgets.browser.plane_scenes.space_pixels(P, points): 3-D points (x, y, z) in canvas
// pixels under a 3-D panel's 3 x 4 map (mplot3d's projection, then the axes' transData).
export function projectSpace(P, points) {
  return points.map(([x, y, z]) => fromHomogeneous(P.map((r) => r[0] * x + r[1] * y + r[2] * z + r[3])));
}

// Twin: camlab.widgets.projective_plane.twins.lift_view(ray, scale, box, w_max, xlim, ylim), its
// notes (twins.LIFT_NOTES) given: {pointH, point, ends, scaledShown, hit, dot, note}; point, hit and
// dot are null where the twin's are None.
export function liftView(ray, scale, box, wMax, xlim, ylim, notes) {
  const [x, y, w] = ray;
  const pointH = ray.map((c) => scale * c);
  const ideal = Math.abs(w) < 1e-12;
  const reach = Math.min(box / Math.max(Math.abs(x), Math.abs(y), 1e-12), wMax / Math.max(Math.abs(w), 1e-12));
  const end = ray.map((c) => reach * c);
  const onPlane = !ideal && Math.max(Math.abs(x / w), Math.abs(y / w)) <= box;
  let dot = null, note = notes[2];
  if (x !== 0 || y !== 0 || w !== 0) {
    dot = arrowPlacement(ray, xlim, ylim);
    const off = dot.direction[0] !== 0 || dot.direction[1] !== 0;
    note = ideal ? notes[0] : off ? notes[1] : "";
  }
  return {
    pointH,
    point: ideal ? null : [x / w, y / w],
    ends: [end.map((c) => -c), end],
    scaledShown: Math.abs(scale) > 1e-12,
    hit: onPlane ? [x / w, y / w, 1] : null,
    dot,
    note,
  };
}

// Twin: Python's format(x, f"+.{digits}f"): the sign always shown (-0 keeps its minus).
export function plusFixed(x, digits) {
  const r = formatFixed(x, digits);
  return r.startsWith("-") ? r : `+${r}`;
}

// Twin: camlab.widgets.projective_plane.twins.normal_line(angle_deg, distance): (cos t, sin t, -d).
export function normalLine(angleDeg, distance) {
  const t = (angleDeg * Math.PI) / 180;
  return [Math.cos(t), Math.sin(t), -distance];
}

// Twin: camlab.projective.is_on_line(x, l, tol): |x . l| <= tol |x| |l|.
export function isOnLine(x, l, tol = 1e-9) {
  const n = (v) => Math.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  return Math.abs(x[0] * l[0] + x[1] * l[1] + x[2] * l[2]) <= tol * n(x) * n(l);
}

// Twin: camlab.widgets.projective_plane.twins.duality_caption(point, line, xlim, ylim): the line
// under point_line_duality's panels (p . l, whether p is on l, where l* is when off the dual panel).
export function dualityCaption(point, line, xlim, ylim) {
  const incidence = point[0] * line[0] + point[1] * line[1] + point[2] * line[2];
  const on = isOnLine(point, line, 1e-3);
  const { direction } = arrowPlacement(line, xlim, ylim);
  const ld = fromHomogeneous(line);
  const off = direction[0] !== 0 || direction[1] !== 0
    ? `; l* = (${formatFixed(ld[0] + 0, 1)}, ${formatFixed(ld[1] + 0, 1)}) is off the dual panel (arrow)`
    : "";
  return `p · l = ${plusFixed(incidence, 3)}: ${on ? "p is on l, and l* is on p*" : "p is not on l, and l* is not on p*"}${off}`;
}

function norm3(v) {
  return Math.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

// Twin: camlab.widgets.projective_plane.twins.line_at_angle(angle_deg, offset): the join of
// (0, offset) and (cos t, offset + sin t).
export function lineAtAngle(angleDeg, offset) {
  const t = (angleDeg * Math.PI) / 180;
  return join([0, offset], [Math.cos(t), offset + Math.sin(t)]);
}

// Twin: camlab.widgets.projective_plane.twins.meet_or_none(l, m): l x m, or null for one line (as
// camlab.projective.meet refuses it: |l x m| < 1e-9 |l| |m|).
export function meetOrNull(l, m) {
  const c = cross(l, m);
  return norm3(c) / (norm3(l) * norm3(m)) < 1e-9 ? null : c;
}

// Twin: camlab.widgets.projective_plane.twins.meet_w_curve(l1, angle1, angles, offset, gap): |w| of
// each unit meet of l1 with the lines through (0, offset) at `angles`; NaN within `gap` degrees of
// angle1 when (0, offset) lies on l1 (every line meets l1 there but l1 itself).
export function meetWCurve(l1, angle1, angles, offset, gap = 1.0) {
  const through = cross(l1, lineAtAngle(angle1, offset)).every((c) => Math.abs(c) < 1e-12);
  return angles.map((a) => {
    if (through && Math.abs(a - angle1) < gap) return NaN;
    const c = cross(l1, lineAtAngle(a, offset));
    return Math.abs(c[2]) / norm3(c);
  });
}

// Twin: camlab.widgets.projective_plane.twins.cross_ratio_homography(h31, h32, angle_deg): a turn by
// the angle with the perspective row (h31, h32, 1).
export function crossRatioHomography(h31, h32, angleDeg) {
  const t = (angleDeg * Math.PI) / 180;
  return [[Math.cos(t), -Math.sin(t), 0], [Math.sin(t), Math.cos(t), 0], [h31, h32, 1]];
}

// Twin: camlab.projective.cross_ratio(points) for four collinear Euclidean points A, B, C, D:
// |l a c| |l b d| / (|l b c| |l a d|), the points scaled to unit length, l the line through the pair
// farthest apart on the unit sphere, normalised.
export function crossRatio(points) {
  const xu = points.map(([x, y]) => {
    const n = Math.sqrt(x * x + y * y + 1);
    return [x / n, y / n, 1 / n];
  });
  let line = null, best = -1;
  for (let i = 0; i < 4; i++) {
    for (let j = i + 1; j < 4; j++) {
      const c = cross(xu[i], xu[j]);
      if (norm3(c) > best) [best, line] = [norm3(c), c];
    }
  }
  line = line.map((c) => c / best);
  const det = (u, v) => det3([line, u, v]);
  const [a, b, c, d] = xu;
  return (det(a, c) * det(b, d)) / (det(b, c) * det(a, d));
}

// Twin: camlab.widgets.projective_plane.twins.ab_over_bc(points): |B - A| / |C - B|.
export function abOverBc(p) {
  return Math.hypot(p[1][0] - p[0][0], p[1][1] - p[0][1]) / Math.hypot(p[2][0] - p[1][0], p[2][1] - p[1][1]);
}

// Twin: camlab.widgets.projective_plane.twins.label_offset(points): 10 points along the normal of
// the line through the first and last point, on its upper side.
export function labelOffset(points) {
  const a = points[0], b = points[points.length - 1];
  const d = [b[0] - a[0], b[1] - a[1]];
  const n = Math.hypot(d[0], d[1]);
  const up = [-d[1] / n, d[0] / n];
  return up[1] >= 0 ? [10 * up[0], 10 * up[1]] : [-10 * up[0], -10 * up[1]];
}

// Twin: camlab.widgets.projective_plane.twins.cross_ratio_caption(points, mapped).
export function crossRatioCaption(points, mapped) {
  const f = (x) => formatFixed(x, 4);
  return (
    `(A, B; C, D): before ${f(crossRatio(points))}, after ${f(crossRatio(mapped))}      ` +
    `AB / BC: before ${f(abOverBc(points))}, after ${f(abOverBc(mapped))}`
  );
}

// Twin: camlab.camera.rotation_x / rotation_y / rotation_z(angle): right-handed, radians.
export function rotationX(a) {
  const c = Math.cos(a), s = Math.sin(a);
  return [[1, 0, 0], [0, c, -s], [0, s, c]];
}
export function rotationY(a) {
  const c = Math.cos(a), s = Math.sin(a);
  return [[c, 0, s], [0, 1, 0], [-s, 0, c]];
}
export function rotationZ(a) {
  const c = Math.cos(a), s = Math.sin(a);
  return [[c, -s, 0], [s, c, 0], [0, 0, 1]];
}

// Twin: numpy.linalg.inv for a 3x3 matrix (its adjugate over its determinant).
export function inv3(M) {
  const d = det3(M);
  const [[a, b, c], [e, f, g], [h, i, j]] = M;
  return [
    [(f * j - g * i) / d, (c * i - b * j) / d, (b * g - c * f) / d],
    [(g * h - e * j) / d, (a * j - c * h) / d, (c * e - a * g) / d],
    [(e * i - f * h) / d, (b * h - a * i) / d, (a * f - b * e) / d],
  ];
}

function transpose(M) {
  return M[0].map((_, j) => M.map((row) => row[j]));
}

function apply(M, v) {
  return M.map((row) => row.reduce((s, m, k) => s + m * v[k], 0));
}

// Twin: camlab.fixtures.ground_plane_view(pitch, yaw, focal, size, height) (radians, pixels, metres):
// the ground grid y = height (lines 1 m apart along z from 0.5 m ahead; across at z = 1.4^k, k < 14)
// seen by the camera R = R_x(pitch) R_y(-yaw) at the origin, K centred; segments clipped at 5 cm.
export function groundPlaneView(pitch, yaw, focal, size, height = 1.5) {
  const [w, h] = size;
  const K = [[focal, 0, (w - 1) / 2], [0, focal, (h - 1) / 2], [0, 0, 1]];
  const R = matmul(rotationX(pitch), rotationY(-yaw));
  const alongZ = Array.from({ length: 25 }, (_, i) => [[i - 12, height, 0.5], [i - 12, height, 2000]]);
  const alongX = Array.from({ length: 14 }, (_, k) => [[-60, height, 1.4 ** k], [60, height, 1.4 ** k]]);
  const near = 0.05;
  const segments = [];
  for (const seg of [...alongZ, ...alongX]) {
    let [a, b] = seg.map((p) => apply(R, p));
    if (a[2] < near && b[2] < near) continue;
    if (a[2] < near || b[2] < near) {
      const s = (near - a[2]) / (b[2] - a[2]);
      const cut = a.map((c, i) => c + s * (b[i] - c));
      if (a[2] < near) a = cut;
      else b = cut;
    }
    segments.push([a, b].map((p) => {
      const uv = apply(K, p);
      return [uv[0] / uv[2], uv[1] / uv[2]];
    }));
  }
  const KR = matmul(K, R);
  return {
    K, R, segments, nAlongZ: alongZ.length,
    vpZ: apply(KR, [0, 0, 1]), vpX: apply(KR, [1, 0, 0]),
    horizon: apply(matmul(transpose(inv3(K)), R), [0, 1, 0]),
  };
}

// Twin: camlab.widgets.projective_plane.twins.rolled_view(pitch, yaw, roll, focal, size) (degrees):
// groundPlaneView, then the image turned by M = K R_z(roll) K^-1 (points by M, lines by M^-T).
export function rolledView(pitch, yaw, roll, focal, size) {
  const rad = Math.PI / 180;
  const g = groundPlaneView(pitch * rad, yaw * rad, focal, size);
  const M = matmul(matmul(g.K, rotationZ(roll * rad)), inv3(g.K));
  return {
    segments: g.segments.map((seg) => mapPoints(M, seg)),
    nAlongZ: g.nAlongZ,
    vpZ: apply(M, g.vpZ),
    vpX: apply(M, g.vpX),
    horizon: apply(transpose(inv3(M)), g.horizon),
  };
}

// The eigenvector of the smallest eigenvalue of a symmetric 3x3 matrix (cyclic Jacobi rotations).
function smallestEigenvector(S) {
  const A = S.map((row) => row.slice());
  const V = [[1, 0, 0], [0, 1, 0], [0, 0, 1]];
  for (let sweep = 0; sweep < 30; sweep++) {
    if (A[0][1] === 0 && A[0][2] === 0 && A[1][2] === 0) break;
    for (const [p, q] of [[0, 1], [0, 2], [1, 2]]) {
      if (A[p][q] === 0) continue;
      const theta = (A[q][q] - A[p][p]) / (2 * A[p][q]);
      const t = (theta >= 0 ? 1 : -1) / (Math.abs(theta) + Math.sqrt(theta * theta + 1));
      const c = 1 / Math.sqrt(t * t + 1), s = t * c;
      for (const M of [A, V]) {
        for (let k = 0; k < 3; k++) {
          const mp = M[k][p], mq = M[k][q];
          M[k][p] = c * mp - s * mq;
          M[k][q] = s * mp + c * mq;
        }
      }
      for (let k = 0; k < 3; k++) {
        const ap = A[p][k], aq = A[q][k];
        A[p][k] = c * ap - s * aq;
        A[q][k] = s * ap + c * aq;
      }
    }
  }
  const k = [0, 1, 2].reduce((best, i) => (A[i][i] < A[best][best] ? i : best), 0);
  return V.map((row) => row[k]);
}

// Twin: camlab.projective.normalise_points for one point: w = 1, or a unit (x, y) when ideal.
export function normalisePoint(x) {
  const scale = x[2] === 0 ? Math.hypot(x[0], x[1]) : x[2];
  return x.map((c) => c / scale);
}

// Twin: camlab.projective.normalise_lines for one line: a^2 + b^2 = 1.
export function normaliseLine(l) {
  const ab = Math.hypot(l[0], l[1]);
  const scale = ab === 0 ? l[2] : ab;
  return l.map((c) => c / scale);
}

// Twin: camlab.projective.vanishing_point(segments): the v minimising sum (l_i . v)^2 over unit v,
// each segment's line l_i (a^2 + b^2 = 1) after Hartley's conditioning T of all the ends, then
// v = T^-1 v_n; ideal when |w| <= 1e-12 |(x, y)|. (The eigenvector of sum l_i l_i^T, the SVD's
// right singular vector up to sign; the sign is the caller's: drawnVanishingPoint fixes it.)
export function vanishingPoint(segments) {
  const pts = segments.flat();
  const c = [0, 1].map((i) => pts.reduce((s, p) => s + p[i], 0) / pts.length);
  const spread = pts.reduce((s, p) => s + Math.hypot(p[0] - c[0], p[1] - c[1]), 0) / pts.length;
  const s = Math.SQRT2 / spread;
  const lines = segments.map(([a, b]) => normaliseLine(cross(
    [s * a[0] - s * c[0], s * a[1] - s * c[1], 1], [s * b[0] - s * c[0], s * b[1] - s * c[1], 1],
  )));
  const S = [0, 1, 2].map((i) => [0, 1, 2].map((j) => lines.reduce((acc, l) => acc + l[i] * l[j], 0)));
  const e = smallestEigenvector(S);
  const v = [e[0] / s + c[0] * e[2], e[1] / s + c[1] * e[2], e[2]];
  if (Math.abs(v[2]) <= 1e-12 * Math.hypot(v[0], v[1])) v[2] = 0;
  return normalisePoint(v);
}

// Twin: camlab.widgets.projective_plane.twins.drawn_vanishing_point(segments): vanishingPoint, an
// ideal one turned to point right (x > 0, or y > 0 when x = 0).
export function drawnVanishingPoint(segments) {
  const v = vanishingPoint(segments);
  const flip = v[2] === 0 && (v[0] < 0 || (v[0] === 0 && v[1] < 0));
  return v.map((c) => (flip ? -c : c) + 0);
}

// Twin: camlab.projective.horizon(vp1, vp2): the line through them, a^2 + b^2 = 1.
export function horizonLine(vp1, vp2) {
  return normaliseLine(cross(vp1, vp2));
}

// Twin: camlab.widgets.projective_plane.twins.horizon_note(hz, visible, title).
export function horizonNote(hz, visible, title) {
  if (visible) return title;
  const v = Math.abs(hz[1]) > 1e-12 ? -hz[2] / hz[1] : NaN;
  return `horizon above the image: v = ${Number.isFinite(v) ? formatFixed(v, 0) : "nan"} px at u = 0`;
}

// ---- lesson 06: a conic under a homography ------------------------------------------------------

// Twin: camlab.widgets.projective_plane.twins.conic_homography(angle_deg, aspect, h31, h32): a
// stretch of x, a turn, and the perspective row (h31, h32, 1).
export function conicHomography(angleDeg, aspect, h31, h32) {
  const t = (angleDeg * Math.PI) / 180;
  return [[aspect * Math.cos(t), -Math.sin(t), 0], [aspect * Math.sin(t), Math.cos(t), 0], [h31, h32, 1]];
}

function symmetrised(M) {
  return M.map((row, i) => row.map((m, j) => (m + M[j][i]) / 2));
}

// Twin: camlab.projective.map_conic(H, C): H^-T C H^-1, symmetrised.
export function mapConic(H, C) {
  const Hinv = inv3(H);
  return symmetrised(matmul(matmul(transpose(Hinv), C), Hinv));
}

// Twin: camlab.projective.map_dual_conic(H, C_star): H C* H^T, symmetrised.
export function mapDualConic(H, Cs) {
  return symmetrised(matmul(matmul(H, Cs), transpose(H)));
}

// Twin: camlab.projective.dual_conic(C): the adjugate, rows the cross products of C's columns.
export function dualConic(C) {
  const [c1, c2, c3] = transpose(C);
  return [cross(c2, c3), cross(c3, c1), cross(c1, c2)];
}

// Twin: camlab.projective.map_lines(H, lines): each line l as H^-T l (rows: lines @ H^-1).
export function mapLines(H, lines) {
  return matmul(lines, inv3(H));
}

function solve2(A, b) {
  const d = A[0][0] * A[1][1] - A[0][1] * A[1][0];
  return [(b[0] * A[1][1] - A[0][1] * b[1]) / d, (A[0][0] * b[1] - b[0] * A[1][0]) / d];
}

// Twin: camlab.projective.conic_points(C, n): n points around a real ellipse, x0 + sqrt(k) S^-1
// (cos t, sin t) with S = (A + sqrt(det A) I) / sqrt(tr A + 2 sqrt(det A)) the symmetric square
// root of C's 2 x 2 block (no eigenvectors, whose signs are free: the same C gives the same points).
// NaN rows where numpy raises (not a real ellipse).
export function conicPoints(C, n = 100) {
  let A = [C[0].slice(0, 2), C[1].slice(0, 2)], b = [C[0][2], C[1][2]], c = C[2][2];
  const det = A[0][0] * A[1][1] - A[0][1] * A[1][0];
  const scale = Math.max(...A.flat().map(Math.abs));
  const none = Array.from({ length: n }, () => [NaN, NaN]);
  if (det <= 1e-12 * scale ** 2) return none;
  if (A[0][0] + A[1][1] < 0) [A, b, c] = [A.map((r) => r.map((v) => -v)), b.map((v) => -v), -c];
  const x0 = solve2(A, b.map((v) => -v));
  const Ab = solve2(A, b);
  const k = b[0] * Ab[0] + b[1] * Ab[1] - c;
  if (k <= 0) return none;
  const s = Math.sqrt(A[0][0] * A[1][1] - A[0][1] * A[1][0]);
  const r = Math.sqrt(A[0][0] + A[1][1] + 2 * s);
  const S = [[(A[0][0] + s) / r, A[0][1] / r], [A[1][0] / r, (A[1][1] + s) / r]];
  const step = (2 * Math.PI) / (n - 1);
  return Array.from({ length: n }, (_, i) => {
    const t = i === n - 1 ? 2 * Math.PI : i * step; // numpy.linspace: the last is the stop itself
    const u = solve2(S, [Math.cos(t), Math.sin(t)]);
    return [x0[0] + Math.sqrt(k) * u[0], x0[1] + Math.sqrt(k) * u[1]];
  });
}

function frobenius(M) {
  return Math.sqrt(M.flat().reduce((s, v) => s + v * v, 0));
}

function quadratic(x, M) {
  return x.reduce((s, xi, i) => s + xi * M[i].reduce((t, m, j) => t + m * x[j], 0), 0);
}

function complexDivide([a, b], [c, d]) {
  const n = c * c + d * d;
  return [(a * c + b * d) / n, (b * c - a * d) / n];
}

// Twin: numpy.allclose(a, b, atol=atol) for complex [re, im] pairs (rtol 1e-5, as numpy's default).
function allCloseComplex(a, b, atol) {
  return a.every((z, i) => Math.hypot(z[0] - b[i][0], z[1] - b[i][1]) <= atol + 1e-5 * Math.hypot(...b[i]));
}

// The tangents x = 1, x = -1, y = 1, y = -1 of the unit circle (twins.CONIC_TANGENTS).
const CONIC_TANGENTS = [[1, 0, -1], [1, 0, 1], [0, 1, -1], [0, 1, 1]];

// Twin: camlab.widgets.projective_plane.twins.conic_geometry(angle_deg, aspect, h31, h32, samples):
// the unit circle's image C' (unit norm), its centre and axis ratio, the mapped samples and
// tangents, the residuals, and H I (I = (1, i, 0), complex entries as [re, im], first entry 1).
export function conicGeometry(angleDeg, aspect, h31, h32, samples) {
  const H = conicHomography(angleDeg, aspect, h31, h32);
  const C = [[1, 0, 0], [0, 1, 0], [0, 0, -1]]; // circle_conic((0, 0), 1)
  let Cp = mapConic(H, C);
  const nC = frobenius(Cp);
  Cp = Cp.map((r) => r.map((v) => v / nC));
  const mapped = mapPoints(H, samples);
  const tangents = mapLines(H, CONIC_TANGENTS).map(normaliseLine);
  let Cs = mapDualConic(H, dualConic(C));
  const nS = frobenius(Cs);
  Cs = Cs.map((r) => r.map((v) => v / nS));
  const HI = H.map((row) => [row[0], row[1]]); // H (1, i, 0)
  const IMapped = HI.map((z) => complexDivide(z, HI[0]));
  const sign = Math.sign(Cp[0][0] + Cp[1][1]);
  const [a, b, d] = [Cp[0][0] * sign, Cp[0][1] * sign, Cp[1][1] * sign];
  const big = (a + d + Math.hypot(a - d, 2 * b)) / 2; // the eigenvalues of [[a, b], [b, d]]
  const small = (a * d - b * b) / big;
  return {
    H,
    CMapped: Cp,
    mapped,
    tangents,
    residual: Math.max(...mapped.map(([x, y]) => Math.abs(quadratic([x, y, 1], Cp)))),
    tangentResidual: Math.max(...tangents.map((l) => Math.abs(quadratic(l, Cs)))),
    IMapped,
    fixed: allCloseComplex(IMapped, [[1, 0], [0, 1], [0, 0]], 1e-9),
    axisRatio: Math.sqrt(small / big),
    centre: solve2([Cp[0].slice(0, 2), Cp[1].slice(0, 2)], [-Cp[0][2], -Cp[1][2]]),
  };
}

// Twin: Python's format(x, ".0e"): one significant digit, the exponent signed and of two digits at
// least ("2e-16", "1e+00"). JavaScript rounds a tie up, Python to even: only exact decimal ties
// (2.5, 0.125 ...) differ, which a residual never is.
export function formatExp0(x) {
  const [m, e] = x.toExponential(0).split("e");
  const sign = e.startsWith("-") ? "-" : "+";
  return `${m}e${sign}${e.replace(/^[+-]/, "").padStart(2, "0")}`;
}

// Twin: camlab.widgets.projective_plane.twins.in_square_view(line, lim): whether the line crosses
// the square [-lim, lim]^2.
export function inSquareView(line, lim = 3) {
  return clipLine(line, [-lim, lim], [-lim, lim]).flat().every(Number.isFinite);
}

// Twin: camlab.widgets.projective_plane.twins.conic_caption(g, h31, h32): the three lines under
// conic_under_homography's plots.
export function conicCaption(g, h31, h32) {
  const h = Math.hypot(h31, h32);
  const verdict = g.fixed
    ? "= I: H is a similarity, so it maps every circle to a circle"
    : "≠ I: H is no similarity, so some circles become non-circles";
  const r = g.axisRatio;
  const shape = Math.abs(r - 1) < 5e-4 ? "a circle" : r > 0.99 ? "nearly a circle" : "an ellipse";
  let bounded;
  if (h === 0) bounded = "H keeps l∞ (the line it sends to ∞ is l∞ itself), so C' stays bounded";
  else {
    const seen = inSquareView([h31, h32, 1]) ? "" : ", off the view";
    bounded = `H sends h31 x + h32 y + 1 = 0 to ∞: ${formatFixed(1 / h, 1)} from C's centre (> 1${seen})`;
  }
  const z = ([re, im]) => `${fixed2(re)}${fixed2(im)}i`;
  const HI = g.IMapped;
  return (
    `H I ∝ (1, ${z(HI[1])}, ${z(HI[2])}) ${verdict}\n` +
    `C': axis ratio ${formatFixed(r, 3)}, ${shape}; ${bounded}\n` +
    `max |x'ᵀC'x'| over the 8 points ${formatExp0(g.residual)};  ` +
    `max |l'ᵀC*'l'| over the 4 tangents ${formatExp0(g.tangentResidual)}`
  );
}

// ---- lesson 11: epipolar lines ------------------------------------------------------------------

const K800 = [[800, 0, 319.5], [0, 800, 239.5], [0, 0, 1]];

// Twin: camlab.fixtures.lessons._camera_800(R, eye): 640 x 480, f = 800 px, {K, R, t = -R eye}.
function camera800(R, eye) {
  return { K: K800, R, t: R.map((row) => -dot3(row, eye)) };
}

function lookingAhead(eye) {
  return lookAt(eye, [eye[0] + 0, eye[1] + 1, eye[2] + 0]); // look_at_rotation(eye, eye + [0, 1, 0])
}

// Twin: camlab.fixtures.stereo_pair(baseline, toe_in): two cameras baseline m apart along x, 1 m
// up, looking along +y, each turned toe_in / 2 (radians) towards the other about its own y axis
// (rotation_from_axis_angle([0, turn, 0]) is rotationY(turn)).
export function stereoPair(baseline, toeIn) {
  return [[[-baseline / 2, 0, 1], -toeIn / 2], [[baseline / 2, 0, 1], toeIn / 2]].map(
    ([eye, turn]) => camera800(matmul(rotationY(turn), lookingAhead(eye)), eye),
  );
}

// Twin: camlab.fixtures.forward_pair(baseline, turn): the second camera baseline m ahead (+y) of the
// first, turned by `turn` radians about its y axis.
export function forwardPair(baseline, turn) {
  const eye1 = [0, -1, 1], eye2 = [0, -1 + baseline, 1];
  return [camera800(lookingAhead(eye1), eye1), camera800(matmul(rotationY(turn), lookingAhead(eye2)), eye2)];
}

// Twin: camlab.widgets.epipolar_twins.MOTIONS: the camera pairs by the names the demo's buttons show.
export const MOTIONS = { "sideways (stereo rig)": stereoPair, "forward (driving)": forwardPair };

// Twin: Camera.centre: -R^T t.
export function cameraCentre(cam) {
  return [0, 1, 2].map((j) => -cam.R.reduce((s, row, i) => s + row[j] * cam.t[i], 0));
}

// Twin: camlab.epipolar.normalise_fundamental(F): unit Frobenius norm, the largest entry (rounded to
// 1e-9; the first in row-major order on a tie) positive.
export function normaliseFundamental(F) {
  const n = frobenius(F);
  const a = F.flat().map((v) => v / n);
  let k = 0;
  a.forEach((v, i) => { if (Math.round(Math.abs(v) * 1e9) > Math.round(Math.abs(a[k]) * 1e9)) k = i; });
  const s = Math.sign(a[k]);
  return [0, 1, 2].map((i) => a.slice(3 * i, 3 * i + 3).map((v) => v * s));
}

function skew([x, y, z]) {
  return [[0, -z, y], [z, 0, -x], [-y, x, 0]];
}

// Twin: camlab.epipolar.fundamental_from_cameras(c1, c2) for two cameras: K2^-T [t]x R K1^-1 with
// the relative pose R = R2 R1^T, t = t2 - R t1, normalised (normaliseFundamental).
export function fundamentalFromCameras(c1, c2) {
  const R = matmul(c2.R, transpose(c1.R));
  const t = c2.t.map((v, i) => v - dot3(R[i], c1.t));
  return normaliseFundamental(matmul(matmul(matmul(transpose(inv3(c2.K)), skew(t)), R), inv3(c1.K)));
}

// Twin: camlab.epipolar.epipolar_lines(F, points, image=1): l' = F x, a^2 + b^2 = 1; a NaN row for
// a point at the epipole (|(a, b)| <= 1e-9 |F| |x|).
export function epipolarLines(F, points) {
  const nF = frobenius(F);
  return points.map(([u, v]) => {
    const l = apply(F, [u, v, 1]);
    if (Math.hypot(l[0], l[1]) <= 1e-9 * nF * Math.hypot(u, v, 1)) return [NaN, NaN, NaN];
    return normaliseLine(l);
  });
}

// Twin: Camera.backproject(uv, depth): the world points at camera depth z along each pixel's ray,
// R^T (z K^-1 (u, v, 1) - t).
export function backproject(cam, uv, depths) {
  const Kinv = inv3(cam.K);
  return uv.map(([u, v], i) => {
    const c = apply(Kinv, [u, v, 1]).map((x, k) => x * depths[i] - cam.t[k]);
    return [0, 1, 2].map((j) => c.reduce((s, x, k) => s + x * cam.R[k][j], 0));
  });
}

// Twin: camlab.widgets.epipolar_twins.line_polyline(lines, size): each line's ends on the image's
// left and right edges (u = -0.5, w - 0.5) when mostly horizontal, else on its top and bottom, and
// a NaN row after each.
export function linePolyline(lines, size) {
  const [w, h] = size;
  return lines.flatMap(([a, b, c]) => {
    if (Math.abs(b) >= Math.abs(a)) return [[-0.5, -(a * -0.5 + c) / b], [w - 0.5, -(a * (w - 0.5) + c) / b], [NaN, NaN]];
    if (a !== 0) return [[-(b * -0.5 + c) / a, -0.5], [-(b * (h - 0.5) + c) / a, h - 0.5], [NaN, NaN]];
    return [[NaN, NaN], [NaN, NaN], [NaN, NaN]];
  });
}

// Twin: camlab.widgets.epipolar_twins.projected_segments(cam, segs): world segments as one
// NaN-separated polyline of pixels (cameraProject: NaN for an end behind the camera).
export function projectedSegments(cam, segs) {
  return polylineData(segs.map((seg) => cameraProject(cam, seg)));
}

// Twin: camlab.widgets.epipolar_twins.DEPTHS: 1, ..., 6 m.
export const DEPTHS = [1, 2, 3, 4, 5, 6];

// Twin: camlab.widgets.epipolar_twins.epipolar_view(motion, baseline, toe_in_deg, point, ref): the
// two cameras, F, the point's lines (l' = F x right, l = x x e left), the reference pixels' pencils
// (NaN rows at the left epipole), the depth marks and the epipoles P C', P' C.
export function epipolarView(motion, baseline, toeInDeg, point, ref) {
  const pair = MOTIONS[motion];
  if (!pair) throw new Error(`motion: expected one of ${Object.keys(MOTIONS)}, got ${motion}`);
  const [c1, c2] = pair(baseline, (toeInDeg * Math.PI) / 180);
  const F = fundamentalFromCameras(c1, c2);
  const image = (cam, X) => apply(cam.K, cam.R.map((row, i) => dot3(row, X) + cam.t[i]));
  const e1 = image(c1, cameraCentre(c2)), e2 = image(c2, cameraCentre(c1));
  const pencilRight = epipolarLines(F, ref);
  const pencilLeft = ref.map(([u, v], i) => (Number.isNaN(pencilRight[i][0]) ? [NaN, NaN, NaN] : cross([u, v, 1], e1)));
  const ray = backproject(c1, DEPTHS.map(() => point), DEPTHS);
  return {
    cameras: [c1, c2],
    F,
    lineRight: epipolarLines(F, [point])[0],
    lineLeft: cross([point[0], point[1], 1], e1),
    pencilRight,
    pencilLeft,
    depthPoints: cameraProject(c2, ray),
    epipoles: [e1, e2],
  };
}
