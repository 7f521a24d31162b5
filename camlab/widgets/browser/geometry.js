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

// Twin: camlab.widgets.start_here.arrowhead_size(angle_deg, radius): marker size in points, [7, 15].
export function arrowheadSize(angleDeg, radius = 1.4) {
  const arc = Math.abs((angleDeg * Math.PI) / 180) * radius;
  return Math.min(15, Math.max(7, (15 * arc) / 0.98));
}

// Twin: camlab.widgets.start_here.tip_readout(point): "(+x.xx, -y.yy)" as Python's format of
// round(c, 2) + 0.0 writes it: exact ties (c = k/8, k odd) round half to even, as Python's round
// does (toFixed would round them up), and a value that rounds to zero is "+0.00", never "-0.00".
export function fixed2(c) {
  let r = c.toFixed(2);
  if (Number.isInteger(c * 8) && !Number.isInteger(c * 4)) {
    const n = c * 100; // exact for these dyadic values
    const f = Math.floor(n);
    r = ((f % 2 === 0 ? f : f + 1) / 100).toFixed(2);
  }
  if (r === "-0.00") r = "0.00";
  return r.startsWith("-") ? r : `+${r}`;
}

export function tipReadout([x, y]) {
  return `(${fixed2(x)}, ${fixed2(y)})`;
}
