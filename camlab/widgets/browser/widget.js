// anywidget's entry point: a <canvas> that draws the scene the kernel sent, redrawn on every
// parameter change (each parameter is a synced trait linked to its slider in the browser).
import { drawStackCheck } from "./stack_check.js";
import { drawSimilarTriangles, dragSimilarTriangles } from "./similar_triangles.js";
import { drawThreeCameras } from "./three_cameras.js";
import { drawDollyZoom } from "./dolly_zoom.js";
import { drawEpipolarLines, dragEpipolarLines } from "./epipolar.js";
import { drawHierarchy } from "./hierarchy.js";
import { drawForwardInverse } from "./forward_inverse.js";
import { dragCorners, drawDrag, followDrag } from "./drag.js";
import { drawPinhole } from "./pinhole.js";
import { drawCameraExplorer, drawOpencvVsOpengl } from "./projective_camera.js";
import { drawConic, drawCrossRatio, drawLift, drawParallelLines, drawPointLineDuality, drawVanishingPoints } from "./projective_plane.js";

// The scene drawers by demo name (the scene's "kind"); a new browser-drawn demo adds its own here.
// `drag(scene, [u, v], values, type)`, where a demo takes the mouse, turns a press ("pointerdown") or
// drag at figure pixel (u, v) into the parameters to set (or null): set on the canvas, they reach the
// sliders by their links. `follow(scene, name, values)`, where controls write one another in the
// browser (drag_homography's corner sliders and corners text), gives the parameters to set when
// `name` changed.
const SCENES = {
  stack_check: { draw: drawStackCheck },
  pinhole_projection: { draw: drawPinhole },
  similar_triangles: { draw: drawSimilarTriangles, drag: dragSimilarTriangles },
  three_cameras: { draw: drawThreeCameras },
  dolly_zoom: { draw: drawDollyZoom },
  lift_to_plane: { draw: drawLift },
  point_line_duality: { draw: drawPointLineDuality },
  parallel_lines: { draw: drawParallelLines },
  cross_ratio_invariance: { draw: drawCrossRatio },
  vanishing_points: { draw: drawVanishingPoints },
  conic_under_homography: { draw: drawConic },
  epipolar_lines: { draw: drawEpipolarLines, drag: dragEpipolarLines },
  transformation_hierarchy: { draw: drawHierarchy },
  forward_vs_inverse: { draw: drawForwardInverse },
  drag_homography: { draw: drawDrag, drag: dragCorners, follow: followDrag },
  camera_explorer: { draw: drawCameraExplorer },
  opencv_vs_opengl: { draw: drawOpencvVsOpengl },
};

// The parameters' values by name, a choice's as its chosen option.
function valuesOf(model, scene) {
  const params = {};
  for (const name of scene.params) params[name] = model.get(name);
  for (const [name, options] of Object.entries(scene.choices || {})) params[name] = options[params[name]];
  return params;
}

// Set parameters on the canvas (their links carry them to the controls and the kernel).
function setValues(model, values) {
  if (!values) return false;
  for (const [name, value] of Object.entries(values)) model.set(name, value);
  model.save_changes();
  return true;
}

// A press, and a move with the button held, on the canvas set the parameters the demo's drag names.
function listenToMouse(canvas, model) {
  const onPointer = (event) => {
    const scene = model.get("scene");
    const drag = scene && SCENES[scene.kind] && SCENES[scene.kind].drag;
    if (!drag || !(event.buttons & 1)) return;
    const at = figurePixel(canvas, scene, event);
    if (setValues(model, drag(scene, at, valuesOf(model, scene), event.type))) event.preventDefault();
  };
  canvas.addEventListener("pointerdown", (event) => {
    canvas.setPointerCapture(event.pointerId);
    onPointer(event);
  });
  canvas.addEventListener("pointermove", onPointer);
}

// A canvas event's position in figure pixels (u right, v down), and whether it lies in a box.
function figurePixel(canvas, scene, event) {
  const r = canvas.getBoundingClientRect();
  return [((event.clientX - r.left) * scene.width) / r.width, ((event.clientY - r.top) * scene.height) / r.height];
}
const inBox = (b, [u, v]) => u >= b.left && u <= b.right && v >= b.top && v <= b.bottom;

// A press on a 3-D panel (scene.turn: their boxes), the moves while it is held and its release go to
// the kernel (BrowserView.publish with a scene to build again), where matplotlib turns the panel as
// under ipympl and the scene comes back with the new background. One message at a time: the next
// waits for the kernel's answer, and of the moves waiting only the last is sent.
function listenToTurns(canvas, model) {
  const queue = [];
  let waiting = false, pressed = false;
  const flush = () => {
    if (waiting || !queue.length) return;
    waiting = true;
    model.send(queue.shift());
  };
  model.on("msg:custom", (msg) => {
    if (!msg.turned) return;
    waiting = false;
    flush();
  });
  const send = (event, type) => {
    const [u, v] = figurePixel(canvas, model.get("scene"), event);
    if (type === "pointermove" && queue.length && queue[queue.length - 1].type === type) queue.pop();
    queue.push({ type, u, v, button: event.button + 1 }); // matplotlib's buttons count from 1
    flush();
  };
  canvas.addEventListener("pointerdown", (event) => {
    const scene = model.get("scene");
    if (!scene || !(scene.turn || []).some((b) => inBox(b, figurePixel(canvas, scene, event)))) return;
    pressed = true;
    send(event, "pointerdown");
  });
  canvas.addEventListener("pointermove", (event) => pressed && send(event, "pointermove"));
  const release = (event) => {
    if (!pressed) return;
    pressed = false;
    send(event, "pointerup");
  };
  canvas.addEventListener("pointerup", release);
  canvas.addEventListener("pointercancel", release);
  canvas.addEventListener("contextmenu", (event) => {
    const scene = model.get("scene");
    if (scene && (scene.turn || []).some((b) => inBox(b, figurePixel(canvas, scene, event)))) event.preventDefault();
  }); // the right button zooms a 3-D panel, as under ipympl
}

function render({ model, el }) {
  const canvas = document.createElement("canvas");
  canvas.className = "camlab-browser-canvas";
  el.appendChild(canvas);
  const ctx = canvas.getContext("2d");
  const background = new Image();
  let ready = false;
  const listening = new Set(); // the parameters already redrawn on
  const draw = () => {
    const scene = model.get("scene");
    if (!ready || !scene || !scene.kind) return;
    const params = valuesOf(model, scene);
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.clearRect(0, 0, canvas.width, canvas.height);
    ctx.setTransform(canvas.width / scene.width, 0, 0, canvas.height / scene.height, 0, 0);
    const k = scene.backgroundScale || 1; // drawn at its own size: the figure's height may end in half a pixel
    ctx.drawImage(background, 0, 0, background.naturalWidth / k, background.naturalHeight / k);
    SCENES[scene.kind].draw(ctx, scene, params);
  };
  const load = () => {
    const scene = model.get("scene");
    if (!scene || !scene.kind) return;
    const dpr = Math.min(window.devicePixelRatio || 1, 2); // the background is sent at 2x
    canvas.width = Math.round(scene.width * dpr);
    canvas.height = Math.round(scene.height * dpr);
    canvas.style.width = `${scene.width}px`;
    canvas.style.height = `${scene.height}px`;
    canvas.setAttribute("role", "img");
    canvas.setAttribute("aria-label", model.get("alt") || "");
    ready = false;
    background.onload = () => {
      ready = true;
      draw();
    };
    background.src = scene.background;
    for (const name of scene.params.filter((n) => !listening.has(n))) {
      model.on(`change:${name}`, () => {
        const follow = SCENES[model.get("scene").kind].follow;
        if (!follow) return draw();
        // after the link that set `name` is done: a link is deaf while it sets, so a value set
        // back within it (a slider stopped short) would not reach its control
        queueMicrotask(() => {
          const now = model.get("scene");
          if (!setValues(model, follow(now, name, valuesOf(model, now)))) draw(); // else drawn on its change
        });
      });
      listening.add(name);
    }
  };
  listenToMouse(canvas, model);
  listenToTurns(canvas, model);
  model.on("change:scene", load);
  model.on("change:alt", () => canvas.setAttribute("aria-label", model.get("alt") || ""));
  load();
}

export default { render };
