import { arrowPlacement, clipLine, conicCaption, conicGeometry, conicPoints, crossRatioCaption, crossRatioHomography, drawnVanishingPoint, dualityCaption, horizonLine, horizonNote, labelOffset, liftView, lineAtAngle, mapPoints, meetOrNull, meetWCurve, normalLine, normalisePoint, polylineData, projectSpace, rolledView } from "./geometry.js";
// (one line: esm_source drops the lines that start with "import")
// Lesson 06's demos drawn in the browser: each drawer is the twin of its demo's update in
// camlab/widgets/projective_plane (the arithmetic in geometry.js, each function's numpy twin named there).
import { arrow, boxedText, clipTo, dot, label, marker, plus, polyline, textLines, times } from "./drawing.js";

// Draw in one panel ({toPixels, box, xlim, ylim}), clipped to its axes as matplotlib clips lines:
// `paint(px, panel)` gets the data-to-pixel map for point lists.
export function inPanel(ctx, panel, paint) {
  ctx.save();
  clipTo(ctx, panel.box);
  paint((pts) => mapPoints(panel.toPixels, pts), panel);
  ctx.restore();
}

// Twin: camlab.plotting.plane.set_line: the infinite line (a, b, c) across the panel, as drawn.
export function lineInPanel(line, panel) {
  return clipLine(line, panel.xlim, panel.ylim);
}

// Twin: camlab.widgets.projective_plane.point_line_duality's update: p and l (primal), p* and l*
// (dual, an arrow at the edge when l* is off the panel), the caption under both.
export function drawPointLineDuality(ctx, scene, v) {
  const p = [v.px, v.py, 1];
  const line = normalLine(v.line_angle, v.line_dist);
  const [primal, dual] = scene.panels;
  const st = scene.styles;
  inPanel(ctx, primal, (px) => {
    dot(ctx, px([[p[0], p[1]]])[0], st.point);
    polyline(ctx, px(lineInPanel(line, primal)), st.line);
  });
  const place = arrowPlacement(line, dual.xlim, dual.ylim);
  inPanel(ctx, dual, (px) => {
    polyline(ctx, px(lineInPanel(p, dual)), st.dualLine);
    if (place.direction[0] === 0 && place.direction[1] === 0) dot(ctx, px([place.position])[0], st.dualPoint);
  });
  if (place.direction[0] !== 0 || place.direction[1] !== 0) {
    const tip = place.position, tail = tip.map((c, i) => c - 0.9 * place.direction[i]);
    const [a, b] = mapPoints(dual.toPixels, [tail, tip]);
    arrow(ctx, a, b, st.arrow);
  }
  textLines(ctx, dualityCaption(p, line, dual.xlim, dual.ylim), st.caption);
  return place;
}

// Twin: camlab.widgets.projective_plane.parallel_lines' update: l1 and l2 and their meet (an arrow
// at the edge when it is off the panel or ideal), |w| against l2's angle, the note for l2 = l1.
export function drawParallelLines(ctx, scene, v) {
  const [plane, wPanel] = scene.panels;
  const st = scene.styles;
  const l2 = lineAtAngle(v.angle2, v.offset2);
  const x = meetOrNull(scene.l1, l2);
  const place = x && arrowPlacement(x, plane.xlim, plane.ylim);
  const off = place && (place.direction[0] !== 0 || place.direction[1] !== 0);
  inPanel(ctx, plane, (px) => {
    polyline(ctx, px(lineInPanel(scene.l1, plane)), st.l1);
    polyline(ctx, px(lineInPanel(l2, plane)), st.l2);
    if (place && !off) dot(ctx, px([place.position])[0], st.meet);
  });
  if (off) {
    const tip = place.position, tail = tip.map((c, i) => c - 1.2 * place.direction[i]);
    const [a, b] = mapPoints(plane.toPixels, [tail, tip]);
    arrow(ctx, a, b, st.arrow);
  }
  const w = meetWCurve(scene.l1, scene.angle1, scene.angles, v.offset2);
  inPanel(ctx, wPanel, (px) => polyline(ctx, px(scene.angles.map((a, i) => [a, w[i]])), st.curve));
  if (!x) boxedText(ctx, scene.note, st.note);
  else dot(ctx, mapPoints(wPanel.toPixels, [[v.angle2, Math.abs(x[2] / Math.hypot(...x))]])[0], st.wDot);
  return x;
}

// Twin: camlab.widgets.projective_plane.cross_ratio_invariance's update: the grid, the line and the
// four points under H, their letters beside the line, and the caption with the two ratios.
export function drawCrossRatio(ctx, scene, v) {
  const H = crossRatioHomography(v.h31, v.h32, v.angle);
  const q = mapPoints(H, scene.points);
  const st = scene.styles;
  const pt = scene.pxPerPoint;
  inPanel(ctx, scene.panel, (px) => {
    polyline(ctx, px(polylineData(scene.grid.map((seg) => mapPoints(H, seg)))), st.grid);
    polyline(ctx, px(q), st.line);
    for (const at of px(q)) dot(ctx, at, st.points);
  });
  const [dx, dy] = labelOffset(q);
  mapPoints(scene.panel.toPixels, q).forEach(([x, y], i) => label(ctx, scene.names[i], [x + dx * pt, y - dy * pt], st.label));
  textLines(ctx, crossRatioCaption(scene.points, q), st.caption);
  return q;
}

// Twin: camlab.widgets.projective_plane.vanishing_points' update: the two families of ground lines,
// the horizon through the two estimated vanishing points, each point a dot or (off the image) an
// arrowhead on the horizon pointing to it, and the title (a note when the horizon is above the image).
export function drawVanishingPoints(ctx, scene, v) {
  const g = rolledView(v.pitch, v.yaw, v.roll, v.focal, scene.size);
  const n = g.nAlongZ, segs = g.segments;
  const vpZ = drawnVanishingPoint(segs.slice(0, n));
  const vpX = segs.length - n >= 2 ? drawnVanishingPoint(segs.slice(n)) : normalisePoint(g.vpX);
  const hz = horizonLine(vpZ, vpX);
  const panel = scene.panel, st = scene.styles;
  const ends = clipLine(hz, scene.box[0], scene.box[1]);
  const visible = ends.flat().every(Number.isFinite);
  const anchor = visible ? [(ends[0][0] + ends[1][0]) / 2, (ends[0][1] + ends[1][1]) / 2] : null;
  inPanel(ctx, panel, (px) => {
    polyline(ctx, px(polylineData(segs.slice(0, n))), st.gridZ);
    polyline(ctx, px(polylineData(segs.slice(n))), st.gridX);
    polyline(ctx, px(ends), st.horizon);
  });
  const px = (pts) => mapPoints(panel.toPixels, pts);
  for (const [vp, style] of [[vpZ, st.vz], [vpX, st.vx]]) {
    const { position, direction } = arrowPlacement(vp, panel.xlim, panel.ylim, anchor);
    const [at, ahead] = px([position, [position[0] + direction[0], position[1] + direction[1]]]);
    if (direction[0] === 0 && direction[1] === 0) dot(ctx, at, style);
    else marker(ctx, at, [ahead[0] - at[0], ahead[1] - at[1]], scene.arrow, style);
  }
  const note = st.note;
  textLines(ctx, horizonNote(hz, visible, scene.title), { ...note, color: visible ? note.color : scene.noteColor });
  return { vpZ, vpX, hz };
}

// Twin: camlab.widgets.projective_plane.conic_under_homography's update: the line H sends to
// infinity (left, none when H keeps l_inf); C' = H^-T C H^-1, the four mapped tangents, the image
// of C's centre (+), C''s centre (x) and the eight mapped points (right, in a full draw's order);
// the caption.
export function drawConic(ctx, scene, v) {
  const g = conicGeometry(v.angle, v.aspect, v.h31, v.h32, scene.samples);
  const [before, after] = scene.panels;
  const st = scene.styles;
  if (v.h31 !== 0 || v.h32 !== 0) {
    inPanel(ctx, before, (px) => polyline(ctx, px(lineInPanel([v.h31, v.h32, 1], before)), st.toInfinity));
  }
  inPanel(ctx, after, (px) => {
    polyline(ctx, px(conicPoints(g.CMapped, 200)), st.conic);
    for (const t of g.tangents) polyline(ctx, px(lineInPanel(t, after)), st.tangent);
    plus(ctx, px([[0, 0]])[0], st.centreImage);
    times(ctx, px([g.centre])[0], st.centreConic);
    for (const at of px(g.mapped)) dot(ctx, at, st.mapped);
  });
  textLines(ctx, conicCaption(g, v.h31, v.h32), st.caption);
  return g;
}

// Twin: camlab.widgets.projective_plane.lift_to_plane's update: the ray through 0 in the 3-D box,
// λ(x, y, w) on it (hidden at λ = 0) and its meet with w = 1 (left, projected as mplot3d projects
// them); the point in the plane w = 1, an arrowhead at the edge when it is off the view or ideal,
// and the note over it (right).
export function drawLift(ctx, scene, v) {
  const { space, plane, styles: st } = scene;
  const g = liftView([v.x, v.y, v.w], v.scale, scene.box, scene.wMax, plane.xlim, plane.ylim, scene.notes);
  ctx.save();
  clipTo(ctx, space.box);
  const px = (pts) => projectSpace(space.toPixels, pts);
  polyline(ctx, px(g.ends), st.ray);
  if (g.scaledShown) dot(ctx, px([g.pointH])[0], st.scaled);
  if (g.hit) dot(ctx, px([g.hit])[0], st.hit);
  ctx.restore();
  if (g.dot) {
    inPanel(ctx, plane, (px2) => {
      const { position, direction } = g.dot;
      const [at, ahead] = px2([position, [position[0] + direction[0], position[1] + direction[1]]]);
      if (direction[0] === 0 && direction[1] === 0) dot(ctx, at, st.dot);
      else marker(ctx, at, [ahead[0] - at[0], ahead[1] - at[1]], scene.arrow, st.dot);
    });
  }
  if (g.note) boxedText(ctx, g.note, st.note);
  return g;
}
