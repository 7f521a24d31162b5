import { mapPoints, ratiosTitle, similarTrianglesLayout } from "./geometry.js";
// Lesson 01's similar_triangles drawn in the browser: twin of camlab.widgets.pinhole_camera.similar_triangles'
// update (camlab.plotting.optics.update_similar_triangles and its title); a click or drag sets Z and Y.
import { polyline, polygon, dot, label, doubleArrow, onSlider, pixelsToData } from "./drawing.js";

export function drawSimilarTriangles(ctx, scene, p) {
  const lay = similarTrianglesLayout(p.f, p.Z, p.Y, scene.h, scene.rooms);
  const st = scene.styles;
  const px = (pts) => mapPoints(scene.toPixels, pts);
  const at = (pt) => px([pt])[0];
  // in the order a full draw paints them: fills (zorder 1), lines (2), texts (3), the pinhole (5)
  polygon(ctx, px(lay.big), st.big);
  polygon(ctx, px(lay.small), st.small);
  polyline(ctx, px(lay.object), st.object);
  dot(ctx, at(lay.point), st.point);
  polyline(ctx, px(lay.ray), st.ray);
  polyline(ctx, px(lay.planes), st.planes);
  polyline(ctx, px(lay.virtual), st.virtual);
  polyline(ctx, px(lay.real), st.real);
  const t = st.title;
  ratiosTitle(p.f, p.Z, p.Y)
    .split("\n")
    .forEach((line, i) => label(ctx, line, [t.x, t.baselines[i]], t, t.align, "baseline"));
  const box = label(ctx, "pinhole", at(lay.pinhole), st.pinhole);
  const hole = at([0, 0]);
  const below = box.top > hole[1]; // the label under the pinhole: its leader leaves the top of the box
  const sign = below ? -1 : 1;
  const start = (below ? box.top : box.bottom) + sign * st.leader.shrinkA;
  const end = hole[1] - sign * st.leader.shrinkB;
  if ((end - start) * sign > 0) polyline(ctx, [[hole[0], start], [hole[0], end]], st.leader);
  for (const key of ["f", "Z", "Y", "y", "y_real"]) {
    const d = lay.dims[key];
    if (d.shown) doubleArrow(ctx, at(d.a), at(d.b), st.dims[key].arrow);
    label(ctx, d.text, at(d.at), st.dims[key].label, d.ha, d.va);
  }
  dot(ctx, hole, st.pinholeDot);
  return lay.y;
}

// A press or drag at canvas pixel (u, v): the object point there, as the kernel's on_mouse sets it
// (clipped to the sliders' ranges, on their 0.05 m steps); null outside the axes.
export function dragSimilarTriangles(scene, at) {
  const p = pixelsToData(scene.toPixels, scene.axes, at);
  if (!p) return null;
  return { Z: onSlider(p[0], scene.ranges.Z), Y: onSlider(-p[1], scene.ranges.Y) };
}
