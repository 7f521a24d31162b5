import { APPROXIMATIONS, approximationError, cameraProject, dollyZoomCamera, dollyZoomErrors, mapPoints, polylineData, projectSegments, rmsText } from "./geometry.js";
// (one line: esm_source drops the lines that start with "import")
// Lesson 05's dolly_zoom drawn in the browser: twin of camlab.widgets.affine_cameras.dolly_zoom's update
// (the two affine images over the perspective one, their RMS readouts, the error curves and markers).
import { polyline, dot, pathMarker, plus, clipTo, label } from "./drawing.js";

const curvesByOffset = new Map(); // the curves depend on the offset only, as the kernel's cache

// Twin: camlab.widgets.affine_cameras.views.dolly_curves(offset, distances) (corners: the cube's).
export function dollyCurves(scene, offset) {
  const key = `${offset}`;
  if (!curvesByOffset.has(key)) {
    const corners = scene.cube.flat();
    const curves = {};
    for (const model of Object.keys(APPROXIMATIONS)) {
      curves[model] = dollyZoomErrors(
        corners, scene.distances, scene.view[0], scene.view[1], scene.target, scene.f0, scene.d0, model, offset, scene.principalPoint,
      );
    }
    curvesByOffset.set(key, curves);
  }
  return curvesByOffset.get(key);
}

export function drawDollyZoom(ctx, scene, p) {
  const d = p.distance, offset = p.offset;
  const cam = dollyZoomCamera(d, scene.view[0], scene.view[1], scene.target, scene.f0, scene.d0, scene.principalPoint, offset);
  const perspective = polylineData(projectSegments(cam, scene.cube));
  const x0 = cameraProject(cam, [scene.target])[0];
  const corners = scene.cube.flat();
  const rms = {};
  for (const panel of scene.images) {
    const m = panel.model;
    const approximate = APPROXIMATIONS[m];
    const px = (pts) => mapPoints(panel.toPixels, pts);
    const e = approximationError(cam, corners, scene.target, m);
    rms[m] = Math.sqrt(e.reduce((s, v) => s + v * v, 0) / e.length);
    ctx.save();
    clipTo(ctx, panel.box);
    polyline(ctx, px(perspective), panel.under);
    polyline(ctx, px(polylineData(projectSegments(approximate(cam, scene.target), scene.cube))), panel.line);
    ctx.restore();
    const r = panel.readout;
    label(ctx, rmsText(rms[m]), [r.x, r.y], r, "left", "top");
    ctx.save();
    clipTo(ctx, panel.box);
    pathMarker(ctx, px([x0])[0], panel.reference);
    plus(ctx, px([panel.centreAt])[0], panel.centre);
    ctx.restore();
  }
  const err = scene.error;
  const curves = dollyCurves(scene, offset);
  const logPx = (pts) => mapPoints(err.toPixels, pts.map(([x, y]) => [Math.log10(x), Math.log10(y)]));
  ctx.save();
  clipTo(ctx, err.box);
  for (const m of Object.keys(err.curves)) polyline(ctx, logPx(scene.distances.map((x, i) => [x, curves[m][i]])), err.curves[m]);
  ctx.restore();
  for (const m of Object.keys(err.markers)) dot(ctx, logPx([[d, rms[m]]])[0], err.markers[m]); // clip_on=False
  return rms;
}
