import { cornerSlid, dragTableText, dragView, formatCorners, parseCorners, wrapText } from "./corners.js";
import { inv3, mapPoints } from "./geometry.js";
import { drawWarp } from "./hierarchy.js";
import { inPanel } from "./projective_plane.js";
import { boxedText, dot, label, polyline, textLines } from "./drawing.js";
// (one line each: esm_source drops the lines that start with "import")
// Lesson 07's drag_homography drawn in the browser: twin of
// camlab.widgets.homographies.geometry.drag_homography's update (the arithmetic in
// camlab.widgets.homographies.corner_twins.drag_view, its twin dragView in corners.js). The corners
// are a text control, written here alone: by a corner slider (followDrag, the twin of corner_keys)
// and by the mouse dragging a corner (dragCorners); the text reaches the kernel through its link, and
// the kernel's readout follows. The picture is warped as transformation_hierarchy warps it (drawWarp).

const LAST = new WeakMap(); // per scene: the last view that could be drawn (a wrong text keeps it)
const GRABBED = new WeakMap(); // per scene: the corner a press picked (null: none)

// A marker with its halo (palette.halo on a marker): a first pass in the halo's colour, as wide as
// the halo, then the marker (camlab.widgets._transport.halo_in_two_passes).
function haloedDot(ctx, at, style) {
  dot(ctx, at, { size: style.size, color: style.hollow ? "rgba(0, 0, 0, 0)" : style.halo, edge: style.halo, edgeWidth: style.haloWidth });
  dot(ctx, at, style);
}

export function drawDrag(ctx, scene, v) {
  let g = dragView(v, scene.fixed);
  const st = scene.styles;
  let note = g.torn ? scene.torn : "";
  if (g.error) {
    note = `cannot use these corners:\n${wrapText(g.error, 55).slice(0, 3).join("\n")}`;
    g = LAST.get(scene); // the figure keeps the last corners that worked
    if (!g) return null;
  } else {
    LAST.set(scene, g);
  }
  // in the order a full draw paints them: the source panel's line sent to infinity (zorder 2), its
  // table and note (3); then the target's picture (0), lines and markers (2), its frame (2.5), names (3)
  inPanel(ctx, scene.source, (px) => polyline(ctx, px(g.away), st.away));
  textLines(ctx, dragTableText(g.measures.rows), st.numbers);
  if (note) boxedText(ctx, note, st.warning);
  inPanel(ctx, scene.target, (px) => {
    drawWarp(ctx, scene, g.H);
    polyline(ctx, px(g.outline), st.quad);
    polyline(ctx, px(g.dense), st.mappedLine);
    for (const at of px(g.mapped)) dot(ctx, at, st.mappedDots);
    for (const at of px(g.corners)) haloedDot(ctx, at, st.handles);
    haloedDot(ctx, px([g.corners[v.corner]])[0], st.chosen);
  });
  for (const spine of scene.spines) polyline(ctx, spine.points, spine.style);
  const pt = scene.pxPerPoint;
  const at = mapPoints(scene.target.toPixels, g.mapped);
  g.names.visible.forEach((shown, i) => {
    const [dx, dy] = g.names.offsets[i];
    if (shown) label(ctx, scene.names[i], [at[i][0] + dx * pt, at[i][1] - dy * pt], st.names, "center", "center");
  });
  return g;
}

// Twin: camlab.widgets.controls.corner_keys (its kernel side is off here, browser_syncs: one writer,
// so no copy sent back from the kernel undoes a key press): a corner slider moved writes its corner
// into the corners text (cornerSlid, stopped short of a dent); the text changed (typed, dragged) or
// another corner picked, and after a stop, the sliders show the picked corner. The parameters to set
// on the canvas (their links carry them to the text box and the sliders), or null.
export function followDrag(scene, name, v) {
  if (!["corners", "corner", "corner_u", "corner_v"].includes(name)) return null;
  let text = v.corners;
  if (name === "corner_u" || name === "corner_v") {
    if (!Number.isFinite(v[name])) return null; // NaN from a slider: the kernel reports it
    text = cornerSlid(text, v.corner, name, v[name], scene.margin) ?? text;
  }
  const parsed = parseCorners(text);
  if (parsed.error) return null; // being typed: the sliders keep the last corner
  const [u, w] = parsed.corners[v.corner];
  const out = {};
  if (text !== v.corners) out.corners = text;
  if (u !== v.corner_u) out.corner_u = u;
  if (w !== v.corner_v) out.corner_v = w;
  return Object.keys(out).length ? out : null;
}

// A press within scene.radius px of a corner picks it; a move with the button held drags it to the
// pointer (in the target's axes only, as connect_corner_drag takes matplotlib's events).
export function dragCorners(scene, [u, v], values, type) {
  const box = scene.target.box;
  if (u < box.left || u > box.right || v < box.top || v > box.bottom) return null;
  const parsed = parseCorners(values.corners);
  if (parsed.error) return null;
  const corners = parsed.corners;
  if (type === "pointerdown") {
    const gaps = mapPoints(scene.target.toPixels, corners).map(([x, y]) => Math.hypot(x - u, y - v));
    const k = gaps.indexOf(Math.min(...gaps));
    GRABBED.set(scene, gaps[k] <= scene.radius ? k : null);
    return null;
  }
  const k = GRABBED.get(scene);
  if (k === null || k === undefined) return null;
  corners[k] = mapPoints(inv3(scene.target.toPixels), [[u, v]])[0];
  return { corners: formatCorners(corners) };
}
