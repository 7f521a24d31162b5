import { hierarchyView, liveImage, pictureFrom, warpPerspective } from "./homography.js";
import { inPanel } from "./projective_plane.js";
// (one line each: esm_source drops the lines that start with "import")
// Lesson 07's transformation_hierarchy drawn in the browser: twin of
// camlab.widgets.homographies.geometry.transformation_hierarchy's update (the arithmetic in
// camlab.widgets.homographies.twins.hierarchy_view, its twin hierarchyView in homography.js). The
// picture is warped pixel by pixel (warpPerspective, the twin of camlab.warp.warp_perspective's
// numpy path with mirror=True: the same bytes), shrunk to the size it is shown and drawn there, as the kernel's live
// canvas draws imshow(interpolation="nearest"). The readout stays the kernel's.
import { boxedText, dot, polyline, putPixels, textLines } from "./drawing.js";

const WARPS = new WeakMap(); // per scene: the decoded picture, the warp and the canvas it is shown on

function warpTarget(scene) {
  let target = WARPS.get(scene);
  if (!target) {
    const [h, w] = scene.canvasShape;
    target = { picture: pictureFrom(scene.picture), warped: new Uint8ClampedArray(h * w * 4), holder: {} };
    WARPS.set(scene, target);
  }
  return target;
}

// The picture warped by H (warpPerspective) and shown as the kernel's live canvas shows it
// (liveImage: cv2's nearest shrink to its rounded box), unsmoothed. The scene's picture,
// canvasShape, fill and imagePlace (homography_scenes); drag_homography's drawer shares it.
export function drawWarp(ctx, scene, H) {
  const target = warpTarget(scene);
  const [h, w] = scene.canvasShape;
  // mirrored beyond the line H sends to infinity, as the kernel's cv2 warp draws a torn picture
  warpPerspective(target.picture, H, scene.canvasShape, "bilinear", scene.fill, target.warped, true);
  const shown = liveImage(target.warped, w, h, scene.imagePlace);
  putPixels(ctx, target.holder, shown.data, shown.width, shown.height, scene.imagePlace.box);
}

export function drawHierarchy(ctx, scene, v) {
  const g = hierarchyView(v, scene.fixed);
  const panel = scene.panel, st = scene.styles;
  // in the order a full draw paints them: the image (zorder 0), the lines (2), the axes' frame (2.5:
  // animated with the image), the texts (3), the points before H (4) and after (5)
  inPanel(ctx, panel, (px) => {
    drawWarp(ctx, scene, g.H);
    polyline(ctx, px(scene.outline), st.outline);
    polyline(ctx, px(g.grid), st.grid);
    polyline(ctx, px(g.vanishing), st.horizon);
  });
  for (const spine of scene.spines) polyline(ctx, spine.points, spine.style);
  const facts = scene.facts[v.group][g.kind];
  textLines(ctx, facts.text, { ...st.facts, ...facts });
  if (g.torn) boxedText(ctx, scene.torn, st.warning);
  inPanel(ctx, panel, (px) => {
    for (const at of px(scene.before)) dot(ctx, at, st.before);
    for (const at of px(g.diagonal)) dot(ctx, at, st.after);
  });
  return g;
}
