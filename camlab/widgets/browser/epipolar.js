import { arrowPlacement, epipolarView, linePolyline, mapPoints, projectedSegments } from "./geometry.js";
// (one line: esm_source drops the lines that start with "import")
// Lesson 11's epipolar_lines drawn in the browser: twin of camlab.widgets.stereo_rectification.epipolar_lines'
// update (the arithmetic in camlab.widgets.epipolar_twins.epipolar_view, its twin epipolarView in
// geometry.js); the readout stays the kernel's. A click or drag in the left image sets u and v.
import { clipTo, dot, marker, onSlider, pathMarker, pixelsToData, polyline } from "./drawing.js";

function finite(lines) {
  return lines.filter((l) => l.every(Number.isFinite));
}

// Twin: camlab.widgets.stereo_rectification._show_epipole: the epipole e (homogeneous) as a star in
// the image, else an arrow 60 px long at the border pointing to it; nothing when it is ideal.
function showEpipole(ctx, scene, panel, e, px) {
  if (Math.abs(e[2]) < 1e-9 * Math.hypot(...e)) return;
  const st = scene.styles;
  const { position, direction } = arrowPlacement(e, panel.xlim, panel.ylim);
  if (direction[0] === 0 && direction[1] === 0) {
    pathMarker(ctx, px([position])[0], st.epipole);
    return;
  }
  const tail = position.map((c, i) => c - 60 * direction[i]);
  polyline(ctx, px([tail, position]), st.shaft);
  const [at, ahead] = px([position, position.map((c, i) => c + direction[i])]);
  marker(ctx, at, [ahead[0] - at[0], ahead[1] - at[1]], scene.arrow, st.head);
}

export function drawEpipolarLines(ctx, scene, v) {
  const x = [v.u, v.v];
  const g = epipolarView(v.motion, v.baseline, v.toe_in, x, scene.ref);
  const st = scene.styles;
  const size = scene.size;
  // per image, in the order a full draw paints them (zorder, then the order they were made)
  scene.panels.forEach((panel, i) => {
    const px = (pts) => mapPoints(panel.toPixels, pts);
    ctx.save();
    clipTo(ctx, panel.box);
    polyline(ctx, px(projectedSegments(g.cameras[i], scene.segments)), st.wire);
    polyline(ctx, px(linePolyline(finite(i === 0 ? g.pencilLeft : g.pencilRight), size)), st.pencil);
    if (i === 0) {
      dot(ctx, px([x])[0], st.point);
      polyline(ctx, px(linePolyline(finite([g.lineLeft]), size)), st.lineLeft);
    } else {
      polyline(ctx, px(linePolyline(finite([g.lineRight]), size)), st.lineRight);
      for (const at of px(g.depthPoints)) dot(ctx, at, st.depth);
    }
    showEpipole(ctx, scene, panel, g.epipoles[i], px);
    if (i === 0) for (const at of px(scene.ref)) pathMarker(ctx, at, st.ref);
    ctx.restore();
  });
  return g;
}

// A press or drag in the left image: the pixel under the mouse, clipped to the sliders' ranges and
// rounded to their steps (as the kernel's click handler sets them).
export function dragEpipolarLines(scene, at) {
  const panel = scene.panels[0];
  const p = pixelsToData(panel.toPixels, panel.box, at);
  if (!p) return null;
  return { u: onSlider(p[0], scene.ranges.u), v: onSlider(p[1], scene.ranges.v) };
}
