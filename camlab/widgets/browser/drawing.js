// Drawing on a <canvas> for the browser-drawn demos (anywidget's render entry point).
//
// The kernel sends the scene once (model "scene": the static background as a PNG, the
// data-to-canvas-pixel map of every panel, colours and sizes in pixels); each slider move sends
// only the parameters (one synced trait per control, linked to the slider in the browser), and
// the browser computes and draws the moving artists with geometry.js. Primitives take canvas
// pixels (y down); colours come from the scene (camlab.plotting.palette), never from here.

export function polyline(ctx, pts, style) {
  const drawn = pts.filter(([x, y]) => Number.isFinite(x) && Number.isFinite(y));
  if (drawn.length < 2) return;
  ctx.save();
  ctx.lineJoin = style.join || "round";
  ctx.lineCap = style.cap || "butt";
  const trace = () => {
    ctx.beginPath();
    ctx.moveTo(drawn[0][0], drawn[0][1]);
    for (const [x, y] of drawn.slice(1)) ctx.lineTo(x, y);
    if (style.closed) ctx.closePath();
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

export function dot(ctx, [x, y], style) {
  if (!Number.isFinite(x) || !Number.isFinite(y)) return;
  ctx.save();
  ctx.beginPath();
  ctx.arc(x, y, style.size / 2, 0, 2 * Math.PI);
  ctx.fillStyle = style.color;
  ctx.fill();
  ctx.lineWidth = style.edgeWidth;
  ctx.strokeStyle = style.edge || style.color;
  ctx.stroke();
  ctx.restore();
}

// A marker path (matplotlib's custom marker: vertices scaled so the largest coordinate is 0.5,
// times the size) at canvas point `at`, its +x axis along the canvas direction `way`.
export function marker(ctx, at, way, verts, style) {
  const n = Math.hypot(way[0], way[1]);
  if (!(n > 0)) return;
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
  ctx.lineJoin = "round";
  ctx.lineWidth = style.edgeWidth;
  ctx.strokeStyle = style.edge;
  ctx.stroke();
  ctx.restore();
}
