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
// the points the view keeps in sight. `size` is the plane's depth, `axisLength` the axes' length.
export function cameraFigure(cam, size, axisLength, labelOffset, [w, h]) {
  const C = cam.centre;
  const corners = planePoints(cam, [[-0.5, -0.5], [w - 0.5, -0.5], [w - 0.5, h - 0.5], [-0.5, h - 0.5]], size);
  const gap = [NaN, NaN, NaN];
  const frustum = [...corners.flatMap((k) => [C, k, gap]), ...corners, corners[0]];
  const tips = cam.R.map((row) => C.map((c, i) => c + 1.2 * axisLength * row[i]));
  const axes = tips.map((tip) => [C, tip.map((x, i) => C[i] + (x - C[i]) / 1.2)]);
  const [right, down, forward = 0] = labelOffset;
  const k = Math.max(size, 0.5);
  const labelAt = C.map((c, i) => c + k * (right * cam.R[0][i] + down * cam.R[1][i] + forward * cam.R[2][i]));
  return { frustum, corners, axes, tips, labelAt, extent: [C, ...corners, ...tips, labelAt] };
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

export function drawCameraExplorer(ctx, scene, p) {
  const frame = explorerFrame(scene, p);
  const { figure, view } = frame;
  const st = scene.styles;
  const p3 = scene.panel3d, pi = scene.panelImage;
  const onScreen = (pts) => mapPoints(p3.toPixels, lineOnScreen(view.M, pts));
  const at = (X) => mapPoints(p3.toPixels, project3d(view.M, [X]).map(([x, y]) => [x, y]))[0];
  const gap = [NaN, NaN, NaN];
  const world = worldAxes(scene.worldAxisLength);
  const lines = {
    world: scene.segments.flatMap(([a, b]) => [a, b, gap]),
    frustum: figure.frustum,
    centre: [frame.cam.centre],
    thumbnail: frame.thumbnail,
  };
  world.forEach((a, i) => (lines[`worldAxis${i}`] = a.line));
  figure.axes.forEach((a, i) => (lines[`cameraAxis${i}`] = a));
  const texts = { label: figure.labelAt };
  world.forEach((a, i) => (texts[`worldLabel${i}`] = a.tip));
  figure.tips.forEach((tip, i) => (texts[`cameraLabel${i}`] = tip));
  for (const name of scene.order) {
    const style = st[name];
    ctx.save();
    if (name in lines) {
      clipTo(ctx, p3.box);
      const pts = onScreen(lines[name]);
      if (style.marker) dot(ctx, pts[0], style.marker);
      else polyline(ctx, pts, style);
    } else if (name === "plane") {
      clipTo(ctx, p3.box);
      polyline(ctx, onScreen(figure.corners), style);
    } else if (name in texts) {
      label(ctx, style.text, at(texts[name]), style, style.ha, style.va);
    } else if (name === "image") {
      clipTo(ctx, pi.box);
      polyline(ctx, mapPoints(pi.toPixels, frame.image), style);
    } else if (name === "principalPoint") {
      plus(ctx, mapPoints(pi.toPixels, [[frame.cam.K[0][2], frame.cam.K[1][2]]])[0], style);
    }
    ctx.restore();
  }
  return frame;
}
