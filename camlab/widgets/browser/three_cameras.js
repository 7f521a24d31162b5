import { affineApproximation, cameraProject, dollyZoomCamera, mapPoints, matchedPointsInFrame, orthographicMatrix, polylineData, projectPoints, projectSegments } from "./geometry.js";
// (one line: esm_source drops the lines that start with "import")
// Lesson 05's three_cameras drawn in the browser: twin of camlab.widgets.affine_cameras.three_cameras'
// update (camlab.affine.three_images, matched_points_in_frame and the X0 markers); the readout stays
// the kernel's.
import { polyline, dot, pathMarker, clipTo } from "./drawing.js";

const RADIANS = Math.PI / 180;

// The moving artists' data at the sliders' values, as the demo's update computes them.
export function threeCamerasFrame(scene, p) {
  const cam = dollyZoomCamera(
    p.distance, p.azimuth * RADIANS, p.elevation * RADIANS, scene.target, scene.f0, scene.d0, scene.principalPoint,
  );
  const segs = scene.segments;
  const PWeak = affineApproximation(cam, scene.X0);
  const POrth = orthographicMatrix(cam.R, cam.t);
  const a = [], b = [];
  for (const [first, last, samples] of Object.values(scene.parts)) {
    const m = matchedPointsInFrame(cam, PWeak, segs.slice(first, last), scene.size, samples);
    a.push(...m.perspective);
    b.push(...m.affine);
  }
  return {
    perspective: projectSegments(cam, segs),
    weak: projectSegments(PWeak, segs),
    orthographic: projectSegments(POrth, segs),
    references: [cameraProject(cam, [scene.X0])[0], projectPoints(PWeak, [scene.X0])[0], projectPoints(POrth, [scene.X0])[0]],
    gaps: a.map((pa, i) => [pa, b[i]]),
  };
}

export function drawThreeCameras(ctx, scene, p) {
  const frame = threeCamerasFrame(scene, p);
  const st = scene.styles;
  // per panel, in the order a full draw paints them (zorder), clipped to the axes as matplotlib clips
  const layers = [
    [["perspective", frame.perspective]],
    [["ghost", frame.perspective], ["weak", frame.weak], ["gaps", frame.gaps]],
    [["orthographic", frame.orthographic]],
  ];
  scene.panels.forEach((panel, i) => {
    const px = (pts) => mapPoints(panel.toPixels, pts);
    ctx.save();
    clipTo(ctx, panel.box);
    for (const [name, segments] of layers[i]) {
      const line = px(polylineData(segments));
      polyline(ctx, line, st[name]);
      if (name === "gaps") for (const q of line) dot(ctx, q, st.gapDots);
    }
    pathMarker(ctx, px([frame.references[i]])[0], st.reference);
    ctx.restore();
  });
  return frame;
}
