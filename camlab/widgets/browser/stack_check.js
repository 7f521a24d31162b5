import { turnAndScale, mapPoints, turnPath, turnWay, arrowheadSize, tipReadout } from "./geometry.js";
// Lesson 00's stack_check drawn in the browser: twin of camlab.widgets.start_here.stack_check's update.
import { polyline, dot, marker } from "./drawing.js";

export function drawStackCheck(ctx, scene, p) {
  const A = turnAndScale(p.angle, p.scale);
  const moved = mapPoints(A, scene.house);
  const tip = moved[scene.roofTip];
  const path = turnPath(p.angle, p.scale, scene.house[scene.roofTip], scene.arcSamples);
  const middle = Math.floor(scene.arcSamples / 2);
  let way = [path[middle + 1][0] - path[middle - 1][0], path[middle + 1][1] - path[middle - 1][1]];
  if (Math.abs(p.angle) < scene.shortTurnDeg) way = [0, 0];
  const st = scene.styles;
  const arrow = { ...st.arrow, size: arrowheadSize(p.angle) * scene.pxPerPoint };
  // way_radius in widgets/start_here.py: inside the house, or outside both when the house is too small
  const radius = p.scale >= scene.wayInsideMinScale ? scene.wayRadius * p.scale : scene.wayOutsideRadius;
  const arc = turnWay(p.angle, radius, scene.waySweepDeg);
  for (const panel of scene.panels) {
    const T = panel.toPixels;
    const px = (pts) => mapPoints(T, pts);
    polyline(ctx, px(path), st.path);
    const [a, b] = px([path[middle], [path[middle][0] + way[0], path[middle][1] + way[1]]]);
    if (Math.hypot(way[0], way[1]) >= 1e-9) marker(ctx, a, [b[0] - a[0], b[1] - a[1]], scene.arrowhead, arrow);
    if (arc.length) {
      const ends = px([arc[arc.length - 2], arc[arc.length - 1]]);
      polyline(ctx, px(arc), st.way);
      marker(ctx, ends[1], [ends[1][0] - ends[0][0], ends[1][1] - ends[0][1]], scene.arrowhead, st.wayHead);
    }
    polyline(ctx, px(moved), st.house);
    dot(ctx, px([tip])[0], st.tip);
  }
  const r = scene.readout;
  ctx.save();
  ctx.font = r.font;
  ctx.fillStyle = r.color;
  ctx.textBaseline = "top";
  // path_note in widgets/start_here.py: the legend's path or arrowhead is not drawn
  const short = Math.abs(p.angle) < scene.shortTurnDeg ? scene.shortTurnNote : "";
  const note = p.angle === 0 ? (p.scale === 1 ? "  (unmoved: no path)" : "") : short;
  ctx.fillText(tipReadout(tip) + note, r.x, r.y);
  ctx.restore();
  return tipReadout(tip);
}
