import { clipLine, crossRatio, formatFixed, inv3, mapPoints, matmul } from "./geometry.js";
import { mapPolyline, normaliseHomography, splitsAtInfinity } from "./homography.js";
// (one line each: esm_source drops the lines that start with "import")
// The per-move arithmetic of lesson 07's drag_homography drawn in the browser (drag.js draws it).
// Every function has its numpy twin named beside it, and tests/test_browser_corners_parity.py runs
// both under node.

const CORNER_LIMIT_PX = 1e6; // Twin: camlab.widgets.controls.CORNER_LIMIT_PX
const COLLINEAR_TOL = 1e-9; // Twin: camlab.homography.estimation._COLLINEAR_TOL

// Twin: camlab.widgets.controls.format_corners(pts): "u0, v0; u1, v1; ..." with two decimals.
export function formatCorners(pts) {
  return pts.map(([u, v]) => `${formatFixed(u, 2)}, ${formatFixed(v, 2)}`).join("; ");
}

// Python's float() of one coordinate of the corners text (surrounding white space allowed), or NaN
// where Python would raise: digits with an optional sign, point and exponent, or inf / nan.
function pyFloat(text) {
  const t = text.trim();
  if (/^[+-]?(\d+(_\d+)*\.?(\d+(_\d+)*)?|\.\d+(_\d+)*)([eE][+-]?\d+(_\d+)*)?$/.test(t)) return Number(t.replace(/_/g, ""));
  if (/^[+-]?(inf|infinity)$/i.test(t)) return t.startsWith("-") ? -Infinity : Infinity;
  if (/^[+-]?nan$/i.test(t)) return NaN;
  return undefined;
}

// Twin: camlab.widgets.controls.parse_corners(text): {corners} (4 x 2, px) or {error} (its message,
// as the ValueError says it; far-off corners are named with 4 significant digits).
export function parseCorners(text) {
  const rows = String(text).split(";").filter((r) => r.trim());
  const pts = rows.map((r) => r.split(",").map(pyFloat));
  const wrong = pts.length !== 4 || pts.some((p) => p.length !== 2 || p.some((x) => x === undefined));
  if (wrong) return { error: `expected 4 corners 'u, v' (pixels) separated by ';', got ${pyRepr(text)}` };
  const far = pts.findIndex((p) => !p.every((x) => Math.abs(x) <= CORNER_LIMIT_PX));
  if (far >= 0) {
    const [u, v] = pts[far].map(formatG4);
    return { error: `corner ${far + 1} is (${u}, ${v}): expected finite pixel coordinates within ±1e+06` };
  }
  let best = [Infinity, 0, 0];
  for (let i = 0; i < 4; i++) {
    for (let j = 0; j < 4; j++) {
      const d = norm2(pts[i][0] - pts[j][0], pts[i][1] - pts[j][1]);
      if (i !== j && d < best[0]) best = [d, i, j];
    }
  }
  if (best[0] < 1) {
    const [, i, j] = best;
    return { error: `corners ${Math.min(i, j) + 1} and ${Math.max(i, j) + 1} coincide (less than 1 px apart): four corners need four distinct points` };
  }
  return { corners: pts };
}

// Python's repr of a str without quotes or backslashes inside: 'text'.
function pyRepr(text) {
  const s = String(text);
  return s.includes("'") && !s.includes('"') ? `"${s}"` : `'${s.replace(/\\/g, "\\\\").replace(/'/g, "\\'")}'`;
}

// Python's f"{x:.4g}" for a non-finite or large number (what parse_corners names a far corner by).
function formatG4(x) {
  if (Number.isNaN(x)) return "nan";
  if (!Number.isFinite(x)) return x > 0 ? "inf" : "-inf";
  const [m, e] = x.toExponential(3).split("e");
  const exp = Number(e);
  if (exp < -4 || exp >= 4) return `${m.replace(/\.?0+$/, "")}e${exp < 0 ? "-" : "+"}${String(Math.abs(exp)).padStart(2, "0")}`;
  return String(Number(x.toPrecision(4)));
}

// Twin: numpy.linalg.norm of a 2-vector: sqrt(x^2 + y^2), as numpy sums it (not Math.hypot's way).
function norm2(x, y) {
  return Math.sqrt(x * x + y * y);
}

function cross2(a, b) {
  return a[0] * b[1] - a[1] * b[0];
}

// Twin: camlab.widgets.controls.convex_margin(corners): the least distance (px) of a corner from
// the line of a side it is not on, positive inside: > 0 convex, <= 0 a dent or bow tie, -inf flat.
export function convexMargin(q) {
  const e = q.map((p, k) => [q[(k + 1) % 4][0] - p[0], q[(k + 1) % 4][1] - p[1]]);
  let area = 0;
  for (let k = 0; k < 4; k++) area += q[k][0] * q[(k + 1) % 4][1] - q[(k + 1) % 4][0] * q[k][1];
  const lengths = e.map(([x, y]) => norm2(x, y));
  if (area === 0 || !lengths.every((l) => l > 0)) return -Infinity;
  let least = Infinity;
  for (let k = 0; k < 4; k++) {
    for (const j of [2, 3]) {
      const r = q[(k + j) % 4];
      least = Math.min(least, (Math.sign(area) * cross2(e[k], [r[0] - q[k][0], r[1] - q[k][1]])) / lengths[k]);
    }
  }
  return least;
}

// Twin: numpy.round(x, 1): x * 10 rounded half to even, over 10.
function round1(x) {
  const y = x * 10, r = Math.round(y);
  return (r - y === 0.5 && r % 2 !== 0 ? r - 1 : r) / 10;
}

// Twin: camlab.widgets.controls.convex_clamp(margin)(corners, index, wanted): from a convex outline
// (margin at least `margin`) corner `index` moves toward `wanted` only as far as the outline stays
// so (30 halvings, rounded to 0.1 px); from any other outline it goes where asked.
export function convexClamp(margin, corners, index, wanted) {
  const q = corners.map((p) => [...p]);
  const start = [...q[index]];
  const ok = (t) => {
    q[index] = [start[0] + t * (wanted[0] - start[0]), start[1] + t * (wanted[1] - start[1])];
    return convexMargin(q) >= margin;
  };
  if (!ok(0) || ok(1)) return [...wanted];
  let low = 0, high = 1;
  for (let i = 0; i < 30; i++) {
    const mid = 0.5 * (low + high);
    if (ok(mid)) low = mid;
    else high = mid;
  }
  return [round1(start[0] + low * (wanted[0] - start[0])), round1(start[1] + low * (wanted[1] - start[1]))];
}

// Twin: camlab.projective.hartley_normalise(points): centroid to 0, mean distance sqrt(2).
function hartley(p) {
  const n = p.length;
  const c = [p.reduce((s, q) => s + q[0], 0) / n, p.reduce((s, q) => s + q[1], 0) / n];
  const spread = p.reduce((s, q) => s + norm2(q[0] - c[0], q[1] - c[1]), 0) / n;
  const s = Math.SQRT2 / spread;
  return p.map(([x, y]) => [x * s + -s * c[0], y * s + -s * c[1]]);
}

// Twin: camlab.homography.estimation._check_general_position(sn, name): the error for collinear
// Hartley-normalised points (all of them, or 3 of 4), or null.
function generalPosition(sn, name) {
  const m = [0, 1].map((k) => sn.reduce((s, q) => s + q[k], 0) / sn.length);
  const c = sn.map(([x, y]) => [x - m[0], y - m[1]]);
  const [a, b, d] = [c.reduce((s, q) => s + q[0] * q[0], 0), c.reduce((s, q) => s + q[0] * q[1], 0), c.reduce((s, q) => s + q[1] * q[1], 0)];
  const root = Math.sqrt(((a - d) / 2) ** 2 + b * b), mid = (a + d) / 2;
  const [ev0, ev1] = [mid - root, mid + root]; // the 2 x 2 scatter's eigenvalues, ascending
  if (Math.sqrt(Math.max(ev0, 0)) < 1e-7 * Math.sqrt(Math.max(ev1, 1e-300))) {
    return `estimate_homography: all ${sn.length} points in ${name} are collinear, so they do not fix a homography; pick points spread over the plane (at least 4, no 3 on a line)`;
  }
  const triples = [[0, 1, 2], [0, 1, 3], [0, 2, 3], [1, 2, 3]];
  const dets = triples.map(([i, j, k]) => Math.abs(cross2([sn[j][0] - sn[i][0], sn[j][1] - sn[i][1]], [sn[k][0] - sn[i][0], sn[k][1] - sn[i][1]])));
  const least = Math.min(...dets);
  if (least < COLLINEAR_TOL * 4) {
    return `estimate_homography: 3 of the 4 points in ${name} are collinear (points [${triples[dets.indexOf(least)].join(", ")}]); pick points in general position`;
  }
  return null;
}

// The 3 x 3 map sending (1,0,0), (0,1,0), (0,0,1) and (1,1,1) to the four points (homogeneous).
function frameOf(p) {
  const M = [[p[0][0], p[1][0], p[2][0]], [p[0][1], p[1][1], p[2][1]], [1, 1, 1]];
  const lam = inv3(M).map((row) => row[0] * p[3][0] + row[1] * p[3][1] + row[2]);
  return M.map((row) => row.map((c, j) => c * lam[j]));
}

// Twin: camlab.homography.estimate_homography(src, dst) for exactly four pairs in general position:
// {H} (h33 = 1) or {error} (the DegenerateError's message). Four pairs fix H exactly, so instead of
// the DLT's null vector it is written through the frame both quadruples are images of:
// H = F_dst F_src^-1 (H&Z section 2.3, the four-point construction).
export function homographyFromCorners(src, dst) {
  for (const [p, name] of [[src, "src"], [dst, "dst"]]) {
    const error = generalPosition(hartley(p), name);
    if (error) return { error };
  }
  return { H: normaliseHomography(matmul(frameOf(dst), inv3(frameOf(src)))) };
}

// Twin: camlab.homography.mapped_angle(H, corner, d1, d2): the angle in degrees between the images
// of the directions d1 and d2 at the corner (the mapping's derivative there), NaN where H sends the
// corner to infinity.
export function mappedAngle(H, x, d1, d2) {
  const w = H[2][0] * x[0] + H[2][1] * x[1] + H[2][2];
  const f = [0, 1].map((r) => (H[r][0] * x[0] + H[r][1] * x[1] + H[r][2]) / w);
  const J = [0, 1].map((r) => [0, 1].map((c) => (H[r][c] - f[r] * H[2][c]) / w));
  const [e1, e2] = [d1, d2].map((d) => [J[0][0] * d[0] + J[0][1] * d[1], J[1][0] * d[0] + J[1][1] * d[1]]);
  const cos = (e1[0] * e2[0] + e1[1] * e2[1]) / (norm2(...e1) * norm2(...e2));
  return Math.acos(Math.min(1, Math.max(-1, cos))) * (180 / Math.PI);
}

// Twin: numpy.isclose(a, b, rtol): |a - b| <= 1e-8 + rtol |b|, infinities equal to themselves.
function isClose(a, b, rtol) {
  if (!Number.isFinite(a) || !Number.isFinite(b)) return a === b;
  return Math.abs(a - b) <= 1e-8 + rtol * Math.abs(b);
}

// Twin: camlab.widgets.homographies.geometry._shown(x, spec): fixed decimals, ∞, or undefined.
function shown(x, digits) {
  return Number.isFinite(x) ? formatFixed(x, digits) : x === Infinity ? "∞" : "undefined";
}

// Twin: camlab.widgets.homographies.geometry.drag_table_rows(...): (quantity, source, image, verdict).
export function dragTableRows(cr0, cr1, length0, length1, ratio0, ratio1, angle0, angle1) {
  const verdict = (same) => (same ? "kept" : "changes");
  return [
    ["cross-ratio", formatFixed(cr0, 4), formatFixed(cr1, 4), verdict(isClose(cr0, cr1, 1e-3))],
    ["|AD| (px)", formatFixed(length0, 1), shown(length1, 1), verdict(isClose(length0, length1, 1e-3))],
    ["|AB| / |CD|", formatFixed(ratio0, 4), shown(ratio1, 4), verdict(isClose(ratio0, ratio1, 1e-3))],
    ["top-left angle", `${formatFixed(angle0, 1)}°`, `${formatFixed(angle1, 1)}°`, verdict(Math.abs(angle0 - angle1) < 0.1)],
  ];
}

// Twin: camlab.widgets.homographies.geometry._drag_measures(line_pts, m, H) with the square's
// corners `square`: the measures (cross-ratio, |AD|, |AB| / |CD|, top-left angle, source and image;
// a segment whose ends H sends to opposite sides of infinity is infinitely long) and the table's rows.
export function dragMeasures(linePts, m, H, square) {
  const w = linePts.map(([x, y]) => x * H[2][0] + y * H[2][1] + H[2][2]);
  const dist = (p, q) => norm2(q[0] - p[0], q[1] - p[1]);
  const imageLength = (i, j) => (w[i] * w[j] > 0 ? dist(m[i], m[j]) : Infinity);
  const ratio = (a, b) => (a === Infinity && b === Infinity ? NaN : a / b);
  const cr0 = crossRatio(linePts), cr1 = crossRatio(m);
  const length0 = dist(linePts[0], linePts[3]), length1 = imageLength(0, 3);
  const ratio0 = dist(linePts[0], linePts[1]) / dist(linePts[2], linePts[3]);
  const ratio1 = ratio(imageLength(0, 1), imageLength(2, 3));
  const edge = (k) => [square[k][0] - square[0][0], square[k][1] - square[0][1]];
  const angle = mappedAngle(H, square[0], edge(1), edge(3));
  const measures = {
    cross_ratio_source: cr0,
    cross_ratio_image: cr1,
    length_source: length0,
    length_image: length1,
    length_ratio_source: ratio0,
    length_ratio_image: ratio1,
    corner_angle: angle,
  };
  return { measures, rows: dragTableRows(cr0, cr1, length0, length1, ratio0, ratio1, 90, angle) };
}

// Twin: camlab.widgets.homographies.corner_twins.across_line(points): the unit offset (y up) across
// the line through the finite points, on its upper side ([0, 1] for fewer than two).
export function acrossLine(points) {
  const finite = points.filter((p) => p.every(Number.isFinite));
  if (finite.length < 2) return [0, 1];
  const a = finite[0], b = finite[finite.length - 1];
  const d = [b[0] - a[0], b[1] - a[1]];
  const n = Math.max(norm2(...d), 1e-9);
  const e = [d[0] / n, -d[1] / n];
  const perp = [-e[1], e[0]];
  return perp[1] > 0 || (perp[1] === 0 && perp[0] > 0) ? perp : [-perp[0], -perp[1]];
}

// Twin: camlab.widgets.homographies.corner_twins.name_places(points, corners, out_hw): each name's
// offset from its point (points, y up) and whether it is shown.
export function namePlaces(points, corners, outHw) {
  const across = acrossLine(points);
  const shown = [], offsets = [], visible = [];
  for (const p of points) {
    const finite = p.every(Number.isFinite);
    const gap = corners.map((c) => (finite ? norm2(c[0] - p[0], c[1] - p[1]) : Infinity));
    const least = Math.min(...gap);
    const near = corners[gap.indexOf(least)];
    const away = [p[0] - near[0], p[1] - near[1]];
    const side = across[0] * away[0] + across[1] * -away[1] >= 0 ? 1 : -1;
    const k = side * (13 + 7 * Math.abs(across[0]));
    let offset = [k * across[0], k * across[1]];
    if (least < 20) {
      const n = Math.max(norm2(...away), 1e-9);
      const d = [away[0] / n + side * across[0], -away[1] / n + side * across[1]];
      const m = Math.max(norm2(...d), 1e-9);
      offset = [(d[0] / m) * 17, (d[1] / m) * 17];
    }
    const seen = finite && 12 <= p[0] && p[0] <= outHw[1] - 12 && 12 <= p[1] && p[1] <= outHw[0] - 4 && least >= 4 && shown.every((q) => norm2(p[0] - q[0], p[1] - q[1]) >= 14);
    offsets.push(offset);
    visible.push(seen);
    if (seen) shown.push(p);
  }
  return { offsets, visible };
}

// Twin: camlab.widgets.homographies.corner_twins.drag_table_text(rows): the table, monospace.
export function dragTableText(rows) {
  return `${"measured".padEnd(15)}  source    image\n` + rows.map(([name, a, b, verdict]) => `${name.padEnd(15)} ${a.padStart(7)}  ${b.padStart(7)}  ${verdict}`).join("\n");
}

// Twin: textwrap.wrap(text, width) for text without hyphenated words: lines of at most `width`
// characters broken at spaces, a longer word split to fill the line it starts on.
export function wrapText(text, width) {
  const chunks = text.replace(/\s/g, " ").split(/( +)/).filter((c) => c !== "").reverse();
  const lines = [];
  while (chunks.length) {
    const line = [];
    let length = 0;
    if (lines.length && chunks[chunks.length - 1].trim() === "") chunks.pop();
    while (chunks.length && length + chunks[chunks.length - 1].length <= width) {
      const chunk = chunks.pop();
      line.push(chunk);
      length += chunk.length;
    }
    if (chunks.length && chunks[chunks.length - 1].length > width) {
      const chunk = chunks.pop(), room = width - length;
      line.push(chunk.slice(0, room));
      chunks.push(chunk.slice(room));
    }
    if (line.length && line[line.length - 1].trim() === "") line.pop();
    if (line.length) lines.push(line.join(""));
  }
  return lines;
}

// Twin: camlab.widgets.homographies.corner_twins.drag_view(values, fixed): {error} when the corners
// cannot be used, else the corners, H, the tear, the source line H sends to infinity (clipped), A'..D',
// the mapped line and outline (NaN where they pass through infinity), the table and the names' places.
export function dragView(v, fixed) {
  const parsed = parseCorners(v.corners);
  if (parsed.error) return { error: parsed.error };
  const fit = homographyFromCorners(fixed.square, parsed.corners);
  if (fit.error) return { error: fit.error };
  const { H } = fit, corners = parsed.corners;
  const mapped = mapPoints(H, fixed.line);
  return {
    error: null,
    corners,
    H,
    torn: splitsAtInfinity(H, fixed.square),
    away: clipLine(H[2], fixed.xlim, fixed.ylim),
    mapped,
    dense: mapPolyline(H, fixed.line_dense),
    outline: mapPolyline(H, fixed.square_dense),
    measures: dragMeasures(fixed.line, mapped, H, fixed.square),
    names: namePlaces(mapped, corners, fixed.out_hw),
  };
}

// Twin: camlab.widgets.controls.corner_keys' write_corner: a corner slider moved to `value` moves the
// chosen corner's u (or v), stopped short of a dent (convexClamp); the new corners text, or null when
// it stays the same. Only the slider that moved is read, so a slider the kernel is still bringing
// to a newly chosen corner moves nothing.
export function cornerSlid(text, index, name, value, margin) {
  const parsed = parseCorners(text);
  if (parsed.error || !Number.isFinite(value)) return null;
  const corners = parsed.corners;
  const wanted = name === "corner_u" ? [value, corners[index][1]] : [corners[index][0], value];
  corners[index] = convexClamp(margin, corners, index, wanted);
  const out = formatCorners(corners);
  return out === text ? null : out;
}
