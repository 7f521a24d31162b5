import { dot3, inv3, lookAt, mapPoints, matmul, orbitEye, polylineData, projectSegments, rotationZ } from "./geometry.js";
import { fitView, lineOnScreen, project3d } from "./view3d.js";
// (the lines above: esm_source drops the lines that start with "import")
// Lesson 04's camera_explorer drawn in the browser: twin of camlab.widgets.projective_camera's
// explorer (explorer_camera, explorer_plane_size and the update's viewer) and of the parts of
// camlab.plotting.scene3d it moves (CameraArtist, SceneView.fit, clip_segments); the K/R/t/C/P
// readout beside the figure stays the kernel's.
import { clipTo, dot, label, plus, polyline } from "./drawing.js";

const RAD = Math.PI / 180;

// Twin: camlab.camera.intrinsic_matrix(fx, fy, cx, cy, skew).
export function intrinsicMatrix(fx, fy, cx, cy, skew = 0) {
  return [[fx, skew, cx], [0, fy, cy], [0, 0, 1]];
}

// Twin: camlab.widgets.projective_camera.explorer_camera(**p) about the house's centre `target`:
// look at it from the orbit, pan about world Z and roll about z in place, slide along x.
// {K, R, t, centre}.
export function explorerCamera(p, target) {
  const K = intrinsicMatrix(p.fx, p.fy, p.cx, p.cy, p.skew);
  const eye = orbitEye(p.azimuth * RAD, p.elevation * RAD, p.distance, target);
  const R = matmul(matmul(rotationZ(-p.roll * RAD), lookAt(eye, target)), rotationZ(-p.pan * RAD));
  const centre = eye.map((c, i) => c + p.slide * R[0][i]);
  return { K, R, t: R.map((row) => -dot3(row, centre)), centre };
}

// Twin: camlab.widgets.projective_camera.explorer_plane_size(distance, K): 0.4 of the distance,
// shrunk by 0.5 / r where an image corner lies r > 0.5 from the axis per metre of depth.
export function explorerPlaneSize(distance, K) {
  const Ki = inv3(K);
  const corners = [[-0.5, -0.5], [639.5, -0.5], [-0.5, 479.5], [639.5, 479.5]];
  const reach = Math.max(
    ...corners.map(([u, v]) => Math.hypot(Ki[0][0] * u + Ki[0][1] * v + Ki[0][2], Ki[1][0] * u + Ki[1][1] * v + Ki[1][2])),
  );
  return 0.4 * distance * Math.min(1.0, 0.5 / reach);
}

// Twin: camlab.plotting.scene3d._plane_points(camera, uv, size): pixels lifted to depth `size`
// in front of the camera, world (NaN stays NaN).
export function planePoints(cam, uv, size) {
  const Ki = inv3(cam.K);
  return uv.map(([u, v]) => {
    const ray = Ki.map((row) => row[0] * u + row[1] * v + row[2]);
    const c = ray.map((r, i) => r * size - cam.t[i]);
    return [0, 1, 2].map((j) => c[0] * cam.R[0][j] + c[1] * cam.R[1][j] + c[2] * cam.R[2][j]);
  });
}

// Twin: camlab.plotting.wireframes.clip_segments(segments, size) (Liang-Barsky): pixel segments
// cut to the image [-0.5, w - 0.5] x [-0.5, h - 0.5]; NaN where nothing is left.
export function clipSegments(segments, [w, h]) {
  return segments.map(([a, b]) => {
    const d = [b[0] - a[0], b[1] - a[1]];
    let lo = 0, hi = 1;
    let visible = [...a, ...b].every(Number.isFinite);
    for (const [axis, low, high] of [[0, -0.5, w - 0.5], [1, -0.5, h - 0.5]]) {
      for (const [p, q] of [[-d[axis], a[axis] - low], [d[axis], high - a[axis]]]) {
        const r = q / p;
        if (p < 0) lo = Math.max(lo, r);
        if (p > 0) hi = Math.min(hi, r);
        if (p === 0 && q < 0) visible = false;
      }
    }
    if (!(visible && lo <= hi)) return [[NaN, NaN], [NaN, NaN]];
    return [[a[0] + lo * d[0], a[1] + lo * d[1]], [a[0] + hi * d[0], a[1] + hi * d[1]]];
  });
}

// Twin: camlab.plotting.scene3d.CameraArtist's geometry for a camera (update, corners, _axis_tips,
// _label_position, extent_points): the frustum (centre-to-corner rays, then the plane's outline, NaN
// between), the plane's corners, the axes from the centre, their label tips, the label's place and
// the points the view keeps in sight. `size` is the plane's depth, `axisLength` the axes' length
// (null: no axes drawn), `labelOffset` the label's place (null: no label).
export function cameraFigure(cam, size, axisLength, labelOffset, [w, h]) {
  const C = cam.centre;
  const corners = planePoints(cam, [[-0.5, -0.5], [w - 0.5, -0.5], [w - 0.5, h - 0.5], [-0.5, h - 0.5]], size);
  const gap = [NaN, NaN, NaN];
  const frustum = [...corners.flatMap((k) => [C, k, gap]), ...corners, corners[0]];
  const extent = [C, ...corners];
  const out = { frustum, corners, extent };
  if (axisLength !== null) {
    out.tips = cam.R.map((row) => C.map((c, i) => c + 1.2 * axisLength * row[i]));
    out.axes = out.tips.map((tip) => [C, tip.map((x, i) => C[i] + (x - C[i]) / 1.2)]);
    extent.push(...out.tips);
  }
  if (labelOffset !== null) {
    const [right, down, forward = 0] = labelOffset;
    const k = Math.max(size, 0.5);
    out.labelAt = C.map((c, i) => c + k * (right * cam.R[0][i] + down * cam.R[1][i] + forward * cam.R[2][i]));
    extent.push(out.labelAt);
  }
  return out;
}

// The 3-D world of camera_explorer at the sliders' values, as its update leaves the artists:
// the camera, its figure and thumbnail (world), its image (pixels) and the fitted view's projection.
export function explorerFrame(scene, p) {
  const cam = explorerCamera(p, scene.target);
  const size = explorerPlaneSize(p.distance, cam.K);
  const axisLength = Math.min(0.8, Math.max(0.35, 0.3 * size));
  const figure = cameraFigure(cam, size, axisLength, scene.labelOffset, scene.imageSize);
  const pixels = projectSegments(cam, scene.segments);
  const thumbnail = planePoints(cam, polylineData(clipSegments(projectSegments(cam, scene.thumbnail), scene.imageSize)), size);
  const azim = p.azimuth + scene.viewerOffset + scene.panFollow * p.pan;
  // SceneView.fit: the scene, the camera's figure and the world axes' label room
  const L = 1.15 * scene.worldAxisLength;
  const fitted = [...scene.segments.flat(), ...figure.extent, [L, 0, 0], [0, L, 0], [0, 0, L]];
  const view = fitView(fitted, scene.elev, azim, scene.panel3d.viewBox, scene.panel3d.fill);
  return { cam, size, axisLength, figure, thumbnail, image: polylineData(pixels), azim, view };
}

// The world axes: from the origin along X, Y, Z, their labels 1.12 lengths out (draw_world_axes).
function worldAxes(length) {
  return [0, 1, 2].map((i) => {
    const e = [0, 0, 0];
    e[i] = length;
    return { line: [[0, 0, 0], e], tip: e.map((c) => c * 1.12) };
  });
}

const GAP = [NaN, NaN, NaN];

// The world axes' and a camera's parts by the names the scene's styles and order give them
// (camera_scenes.py): world lines (3-D points, NaN between pieces), the plane's corners and texts
// ({at: world point, and what changes of the text: text, ha, va}).
function namedParts(scene, figure, cameraAxes, cameraLabels) {
  const lines = { frustum: figure.frustum, plane: figure.corners };
  const texts = {};
  worldAxes(scene.worldAxisLength).forEach((a, i) => {
    lines[`worldAxis${i}`] = a.line;
    texts[`worldLabel${i}`] = { at: a.tip };
  });
  cameraAxes.forEach((a, i) => (lines[`cameraAxis${i}`] = a));
  cameraLabels.forEach((t, i) => (texts[`cameraLabel${i}`] = t));
  return { lines, texts };
}

// Paint a 3-D panel's artists (projection M) and the image panel's in the scene's order: a line or
// a polygon clipped to its axes (Line3D's masked points break it), a round marker, a text unclipped;
// `flat` holds the image panel's parts in its data coordinates.
function paint(ctx, scene, M, lines, texts, flat = {}) {
  const st = scene.styles;
  const p3 = scene.panel3d, pi = scene.panelImage;
  for (const name of scene.order) {
    const style = st[name];
    ctx.save();
    if (name in lines) {
      clipTo(ctx, p3.box);
      const pts = mapPoints(p3.toPixels, lineOnScreen(M, lines[name]));
      if (style.marker) dot(ctx, pts[0], style.marker);
      else polyline(ctx, pts, style);
    } else if (name in texts) {
      const t = texts[name];
      const [x, y] = project3d(M, [t.at])[0];
      const at = mapPoints(p3.toPixels, [[x, y]])[0];
      label(ctx, t.text ?? style.text, at, style, t.ha ?? style.ha, t.va ?? style.va);
    } else if (name in flat) {
      if (style.cross) plus(ctx, mapPoints(pi.toPixels, flat[name])[0], style.cross); // clip_on=False
      else {
        clipTo(ctx, pi.box);
        polyline(ctx, mapPoints(pi.toPixels, flat[name]), style);
      }
    }
    ctx.restore();
  }
}

export function drawCameraExplorer(ctx, scene, p) {
  const frame = explorerFrame(scene, p);
  const { figure, cam } = frame;
  const { lines, texts } = namedParts(scene, figure, figure.axes, figure.tips.map((at) => ({ at })));
  Object.assign(lines, {
    world: scene.segments.flatMap(([a, b]) => [a, b, GAP]),
    centre: [cam.centre],
    thumbnail: frame.thumbnail,
  });
  texts.label = { at: figure.labelAt };
  paint(ctx, scene, frame.view.M, lines, texts, { image: frame.image, principalPoint: [[cam.K[0][2], cam.K[1][2]]] });
  return frame;
}

// Twin: camlab.plotting.view3d.align_away(ax, text, start, tip): a label at `tip` aligned to run away
// from start -> tip on screen (projection M). [ha, va].
export function alignAway(M, start, tip) {
  const [[x0, y0], [x1, y1]] = project3d(M, [start, tip]);
  return [x1 >= x0 ? "left" : "right", y1 >= y0 ? "bottom" : "top"];
}

// Twin: camlab.widgets.projective_camera.opencv_vs_opengl's update: the camera orbited `orbit`
// degrees about the world's vertical, looking at the target; its axes drawn as R's rows (OpenCV) or
// R_gl's (OpenGL / Blender: rows 2 and 3 flipped), labelled by the frame; the viewer turned half as
// far; the view fitted to the house, the origin, both frames' label tips and the camera.
export function opencvFrame(scene, p) {
  const eye = matmul(rotationZ(p.orbit * RAD), scene.eye.map((c) => [c])).map((row) => row[0]);
  const R = lookAt(eye, scene.target);
  const cam = { K: scene.K, R, t: R.map((row) => -dot3(row, eye)), centre: eye };
  const gl = p.frame !== "OpenCV";
  const axesR = gl ? [R[0], R[1].map((c) => -c), R[2].map((c) => -c)] : R;
  const names = gl ? scene.names.opengl : scene.names.opencv;
  const C = eye;
  const along = (v, k) => C.map((c, i) => c + k * v[i]);
  const labelTips = [...R, R[1].map((c) => -c), R[2].map((c) => -c)].map((row) => along(row, scene.tips));
  const figure = cameraFigure(cam, scene.planeSize, null, null, scene.imageSize);
  const azim = scene.azim0 + scene.follow * p.orbit;
  const view = fitView([...scene.house.flat(), [0, 0, 0], ...labelTips, ...figure.extent], scene.elev, azim, scene.panel3d.viewBox, scene.panel3d.fill);
  const axes = axesR.map((row, i) => {
    const e = along(row, scene.axis);
    const [ha, va] = alignAway(view.M, C, e);
    return { line: [C, e], label: { at: along(row, scene.label), text: names[i], ha, va } };
  });
  return { cam, figure, axes, axesR, view, azim };
}

export function drawOpencvVsOpengl(ctx, scene, p) {
  const frame = opencvFrame(scene, p);
  const { lines, texts } = namedParts(scene, frame.figure, frame.axes.map((a) => a.line), frame.axes.map((a) => a.label));
  Object.assign(lines, { house: scene.house.flatMap(([a, b]) => [a, b, GAP]), centre: [frame.cam.centre] });
  paint(ctx, scene, frame.view.M, lines, texts);
  return frame;
}
