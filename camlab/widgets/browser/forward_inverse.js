import { cropPixels, forwardInverseView, liveImage, pictureFrom } from "./homography.js";
import { polyline, putPixels } from "./drawing.js";
// (one line each: esm_source drops the lines that start with "import")
// Lesson 07's forward_vs_inverse drawn in the browser: twin of
// camlab.widgets.homographies.estimation.forward_vs_inverse's update (the arithmetic in
// camlab.widgets.homographies.twins.forward_inverse_view, its twin forwardInverseView in
// homography.js). Both warps are computed pixel by pixel, as the lesson teaches them: the forward
// warp pushes each source pixel (forwardWarp, byte for byte camlab.warp.forward_warp), the inverse
// warp pulls each output pixel (warpPerspective, byte for byte camlab.warp.warp_perspective's numpy
// path); each panel shows its image as the kernel's live canvas does (liveImage). The readout stays
// the kernel's.

const WORK = new WeakMap(); // per scene: the decoded picture, the warps' buffers, each panel's canvas

function workFor(scene) {
  let work = WORK.get(scene);
  if (!work) {
    work = { picture: pictureFrom(scene.picture), buffers: {}, panels: scene.panels.map(() => ({})) };
    WORK.set(scene, work);
  }
  return work;
}

export function drawForwardInverse(ctx, scene, v) {
  const work = workFor(scene);
  const g = forwardInverseView(v, work.picture, scene.fixed, work.buffers);
  const [h, w] = scene.fixed.shape;
  const zoom = scene.zoom; // top, left, height, width: output px
  const images = {
    forward: [g.shown, w, h],
    forward_zoom: [cropPixels(g.shown, w, zoom), zoom[3], zoom[2]],
    inverse_zoom: [cropPixels(g.inverse, w, zoom), zoom[3], zoom[2]],
    inverse: [g.inverse, w, h],
  };
  // in the order a full draw paints them: axes by axes, the image (zorder 0), the yellow frame (1),
  // the spines (2.5: animated with the image)
  scene.panels.forEach((panel, i) => {
    const shown = liveImage(...images[panel.image], panel.place);
    putPixels(ctx, work.panels[i], shown.data, shown.width, shown.height, panel.place.box);
    for (const frame of panel.frames) polyline(ctx, frame.points, frame.style);
    for (const spine of panel.spines) polyline(ctx, spine.points, spine.style);
  });
  return g;
}
