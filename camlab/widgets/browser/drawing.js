// Drawing on a <canvas> for the browser-drawn demos (anywidget's render entry point).
//
// The kernel sends the scene once (model "scene": the static background as a PNG, the
// data-to-canvas-pixel map of every panel, colours and sizes in pixels); each slider move sends
// only the parameters (one synced trait per control, linked to the slider in the browser), and
// the browser computes and draws the moving artists with geometry.js. Primitives take canvas
// pixels (y down); colours come from the scene (camlab.plotting.palette), never from here.

// Split a polyline at its non-finite points, as matplotlib breaks a line at NaN.
function runs(pts) {
  const out = [[]];
  for (const p of pts) {
    if (Number.isFinite(p[0]) && Number.isFinite(p[1])) out[out.length - 1].push(p);
    else if (out[out.length - 1].length) out.push([]);
  }
  return out.filter((r) => r.length >= 2);
}

// matplotlib's pixel snapping (path.snap, Agg's PathSnapper): a path whose every segment is
// horizontal or vertical (within 1e-4 px), of at most 1024 vertices, has its vertices moved to pixel
// edges, or to pixel centres for a line of odd width (in whole pixels), so it draws crisp.
function snapped(drawn, width) {
  const all = drawn.flat();
  if (all.length > 1024) return drawn;
  for (const run of drawn) {
    for (let i = 1; i < run.length; i++) {
      const [x0, y0] = run[i - 1], [x1, y1] = run[i];
      if (Math.abs(x1 - x0) >= 1e-4 && Math.abs(y1 - y0) >= 1e-4) return drawn;
    }
  }
  const half = Math.round(width) % 2 ? 0.5 : 0.0;
  return drawn.map((run) => run.map(([x, y]) => [Math.floor(x + 0.5) + half, Math.floor(y + 0.5) + half]));
}

export function polyline(ctx, pts, style) {
  let drawn = runs(pts);
  if (!drawn.length) return;
  if (style.snap) drawn = snapped(drawn, style.width);
  ctx.save();
  ctx.lineJoin = style.join || "round";
  ctx.lineCap = style.cap || "butt";
  const trace = () => {
    ctx.beginPath();
    for (const run of drawn) {
      ctx.moveTo(run[0][0], run[0][1]);
      for (const [x, y] of run.slice(1)) ctx.lineTo(x, y);
      if (style.closed) ctx.closePath();
    }
  };
  if (style.halo) {
    ctx.setLineDash(style.haloDash || style.dash || []);
    ctx.strokeStyle = style.halo;
    ctx.lineWidth = style.haloWidth;
    trace();
    ctx.stroke();
  }
  ctx.setLineDash(style.dash || []);
  ctx.strokeStyle = style.color;
  ctx.lineWidth = style.width;
  trace();
  if (style.fill) {
    ctx.fillStyle = style.fill;
    ctx.fill();
  }
  ctx.stroke();
  ctx.restore();
}

// A filled polygon without an edge (matplotlib's fill with lw=0); style.fill is a CSS colour.
export function polygon(ctx, pts, style) {
  if (pts.some(([x, y]) => !Number.isFinite(x) || !Number.isFinite(y))) return;
  ctx.save();
  ctx.beginPath();
  pts.forEach(([x, y], i) => (i === 0 ? ctx.moveTo(x, y) : ctx.lineTo(x, y)));
  ctx.closePath();
  ctx.fillStyle = style.fill;
  ctx.fill();
  ctx.restore();
}

// One line of text at canvas point `at`, aligned as matplotlib aligns it: ha left/center/right,
// va by the "lp" box (style.ascent above the baseline, style.descent below), on a box of colour
// style.box padded by style.pad when given, outlined by style.halo when given. Returns the text's box
// {x0, x1, top, bottom}.
export function label(ctx, text, at, style, ha = "center", va = "center") {
  ctx.save();
  ctx.font = style.font;
  const width = ctx.measureText(text).width;
  const x0 = ha === "left" ? at[0] : ha === "right" ? at[0] - width : at[0] - width / 2;
  const a = style.ascent, d = style.descent;
  const base = { top: at[1] + a, bottom: at[1] - d, baseline: at[1] }[va] ?? at[1] + (a - d) / 2;
  const box = { x0, x1: x0 + width, top: base - a, bottom: base + d };
  if (style.box && text.trim()) {
    const p = style.pad || 0;
    ctx.fillStyle = style.box;
    ctx.fillRect(box.x0 - p, box.top - p, width + 2 * p, a + d + 2 * p);
  }
  ctx.textAlign = "left";
  ctx.textBaseline = "alphabetic";
  if (style.halo) { // palette.halo on a text: its glyphs outlined first, style.haloWidth px wide
    ctx.lineJoin = "round";
    ctx.lineWidth = style.haloWidth;
    ctx.strokeStyle = style.halo;
    ctx.strokeText(text, x0, base);
  }
  ctx.fillStyle = style.color;
  ctx.fillText(text, x0, base);
  ctx.restore();
  return box;
}

// matplotlib's "<->" arrow (ArrowStyle.CurveAB) from a to b, canvas pixels: the shaft and an open
// head at each end, each head's two strokes head_dist = hypot(length, width) long at atan(width /
// length) to the shaft, its tip drawn back by half the line width / sin of that angle. The ends are
// first shrunk by style.shrinkA and style.shrinkB px (annotate's shrinks; 0 when not given).
export function doubleArrow(ctx, a, b, style) {
  arrowBetween(ctx, a, b, style, true);
}

// matplotlib's "->" arrow (ArrowStyle.CurveB) from a to b: doubleArrow with the head at b only.
export function arrow(ctx, a, b, style) {
  arrowBetween(ctx, a, b, style, false);
}

function arrowBetween(ctx, from, to, style, both) {
  const full = Math.hypot(to[0] - from[0], to[1] - from[1]);
  if (!(full > 0)) return;
  const ex = (to[0] - from[0]) / full, ey = (to[1] - from[1]) / full;
  const sa = style.shrinkA || 0, sb = style.shrinkB || 0;
  if (full <= sa + sb) return;
  const a = [from[0] + sa * ex, from[1] + sa * ey], b = [to[0] - sb * ex, to[1] - sb * ey];
  const len = full - sa - sb;
  const headDist = Math.hypot(style.headLength, style.headWidth);
  const cos = style.headLength / headDist, sin = style.headWidth / headDist;
  const back = (0.5 * style.width) / sin;
  const head = (tip, from) => {
    const ux = (from[0] - tip[0]) / len, uy = (from[1] - tip[1]) / len;
    const t = [tip[0] + back * ux, tip[1] + back * uy];
    const dx = ux * headDist, dy = uy * headDist;
    return [
      [t[0] + cos * dx + sin * dy, t[1] - sin * dx + cos * dy],
      t,
      [t[0] + cos * dx - sin * dy, t[1] + sin * dx + cos * dy],
    ];
  };
  const hb = head(b, a);
  const ha = both ? head(a, b) : [null, a, null];
  ctx.save();
  ctx.strokeStyle = style.color;
  ctx.lineWidth = style.width;
  ctx.lineJoin = "miter";
  ctx.lineCap = "butt";
  ctx.beginPath();
  ctx.moveTo(ha[1][0], ha[1][1]);
  ctx.lineTo(hb[1][0], hb[1][1]);
  for (const h of both ? [ha, hb] : [hb]) {
    ctx.moveTo(h[0][0], h[0][1]);
    ctx.lineTo(h[1][0], h[1][1]);
    ctx.lineTo(h[2][0], h[2][1]);
  }
  ctx.stroke();
  ctx.restore();
}

// textLines on a box as matplotlib's bbox draws it: face style.box, edge style.edge (style.edgeWidth
// px), padded by style.pad px around the lines' "lp" boxes and the widest line.
export function boxedText(ctx, text, style) {
  const lines = text.split("\n");
  ctx.save();
  ctx.font = style.font;
  const width = Math.max(...lines.map((line) => ctx.measureText(line).width));
  const x0 = style.align === "left" ? style.x : style.align === "right" ? style.x - width : style.x - width / 2;
  const p = style.pad;
  const top = style.baselines[0] - style.ascent - p;
  const bottom = style.baselines[lines.length - 1] + style.descent + p;
  ctx.fillStyle = style.box;
  ctx.fillRect(x0 - p, top, width + 2 * p, bottom - top);
  ctx.strokeStyle = style.edge;
  ctx.lineWidth = style.edgeWidth;
  ctx.strokeRect(x0 - p, top, width + 2 * p, bottom - top);
  ctx.restore();
  textLines(ctx, text, { ...style, box: null });
}

// A text of one or more lines at the anchor and baselines matplotlib gave it (scenes' text_scene:
// style.x, style.baselines, style.align); its words may change, its number of lines not.
export function textLines(ctx, text, style) {
  text.split("\n").forEach((line, i) => label(ctx, line, [style.x, style.baselines[i]], style, style.align, "baseline"));
}

// A round marker at canvas point (x, y), where Agg stamps it: its draw_markers truncates the
// position + 0.5 to a whole pixel and centres a round marker (no snapping) in that pixel.
export function dot(ctx, [x, y], style) {
  if (!Number.isFinite(x) || !Number.isFinite(y)) return;
  ctx.save();
  ctx.beginPath();
  ctx.arc(Math.floor(x + 0.5) + 0.5, Math.floor(y + 0.5) + 0.5, style.size / 2, 0, 2 * Math.PI);
  ctx.fillStyle = style.color;
  ctx.fill();
  ctx.lineWidth = style.edgeWidth;
  ctx.strokeStyle = style.edge || style.color;
  ctx.stroke();
  ctx.restore();
}

// A marker path (matplotlib's custom marker: vertices scaled so the largest coordinate is 0.5,
// times the size) at canvas point `at`, its +x axis along the canvas direction `way`.
// Placed as dot places a round marker (Agg centres an unsnapped marker in the pixel it stamps).
export function marker(ctx, at, way, verts, style) {
  const n = Math.hypot(way[0], way[1]);
  if (!(n > 0)) return;
  at = [Math.floor(at[0] + 0.5) + 0.5, Math.floor(at[1] + 0.5) + 0.5];
  const c = way[0] / n, s = -way[1] / n; // display y runs up, canvas y down
  const k = 0.5 * style.size;
  ctx.save();
  ctx.beginPath();
  verts.forEach(([vx, vy], i) => {
    const x = at[0] + k * (vx * c - vy * s);
    const y = at[1] - k * (vx * s + vy * c);
    if (i === 0) ctx.moveTo(x, y);
    else ctx.lineTo(x, y);
  });
  ctx.closePath();
  ctx.fillStyle = style.color;
  ctx.fill();
  ctx.lineJoin = style.join || "round";
  ctx.lineWidth = style.edgeWidth;
  ctx.strokeStyle = style.edge;
  ctx.stroke();
  ctx.restore();
}

// A polygon marker (matplotlib's "D", "s" ...) at canvas point `at`: style.verts its outline for a
// size of 1 (y up), style.size in px, filled with style.color and edged with style.edge. It is
// `marker` unturned, at twice the size (marker's vertices span -0.5..0.5), with mitred corners.
export function pathMarker(ctx, at, style) {
  if (!Number.isFinite(at[0]) || !Number.isFinite(at[1])) return;
  marker(ctx, at, [1, 0], style.verts, { ...style, size: 2 * style.size, join: "miter" });
}

// Clip what follows to an axes' box {left, right, top, bottom} (canvas pixels), as matplotlib clips
// a line and its markers to its axes; undone by the caller's ctx.restore().
export function clipTo(ctx, box) {
  ctx.beginPath();
  ctx.rect(box.left, box.top, box.right - box.left, box.bottom - box.top);
  ctx.clip();
}

// Two strokes through canvas point `at`, each from `at` + [dx0, dy0] to `at` + [dx1, dy1] (px), style.width wide.
function strokes(ctx, at, style, ends) {
  if (!Number.isFinite(at[0]) || !Number.isFinite(at[1])) return;
  ctx.save();
  ctx.strokeStyle = style.color;
  ctx.lineWidth = style.width;
  ctx.lineCap = "butt";
  ctx.beginPath();
  for (const [dx0, dy0, dx1, dy1] of ends) {
    ctx.moveTo(at[0] + dx0, at[1] + dy0);
    ctx.lineTo(at[0] + dx1, at[1] + dy1);
  }
  ctx.stroke();
  ctx.restore();
}

// matplotlib's "+" marker at canvas point `at`: two strokes style.size px long, style.width wide.
export function plus(ctx, at, style) {
  const h = style.size / 2;
  strokes(ctx, at, style, [[-h, 0, h, 0], [0, -h, 0, h]]);
}

// matplotlib's "x" marker at canvas point `at`: the diagonals of a square style.size px wide.
export function times(ctx, at, style) {
  const h = style.size / 2;
  strokes(ctx, at, style, [[-h, -h, h, h], [-h, h, h, -h]]);
}

// A mouse position (canvas pixels) in an axes' data coordinates: the inverse of its affine map
// `toPixels` (to_canvas_pixels); null outside the axes' box.
export function pixelsToData(toPixels, box, [u, v]) {
  if (u < box.left || u > box.right || v < box.top || v > box.bottom) return null;
  const T = toPixels;
  const det = T[0][0] * T[1][1] - T[0][1] * T[1][0];
  const du = u - T[0][2], dv = v - T[1][2];
  return [(T[1][1] * du - T[0][1] * dv) / det, (-T[1][0] * du + T[0][0] * dv) / det];
}

// A value clipped to a slider's range {min, max, step} and put on its steps, as the slider shows it.
export function onSlider(value, r) {
  return Math.round(Math.min(r.max, Math.max(r.min, value)) / r.step) * r.step;
}

// An RGBA image (rows from the top) drawn at canvas box {left, top, width, height}, unsmoothed:
// pixel for pixel on a canvas at the figure's size, each pixel a block on a denser screen. `holder`
// keeps its offscreen canvas between draws.
export function putPixels(ctx, holder, data, width, height, box) {
  if (!holder.canvas || holder.canvas.width !== width || holder.canvas.height !== height) {
    holder.canvas = document.createElement("canvas");
    holder.canvas.width = width;
    holder.canvas.height = height;
    holder.ctx = holder.canvas.getContext("2d");
  }
  holder.ctx.putImageData(new ImageData(data, width, height), 0, 0);
  ctx.save();
  ctx.imageSmoothingEnabled = false;
  ctx.drawImage(holder.canvas, 0, 0, width, height, box.left, box.top, box.width, box.height);
  ctx.restore();
}
