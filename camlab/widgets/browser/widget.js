// anywidget's entry point: a <canvas> that draws the scene the kernel sent, redrawn on every
// parameter change (each parameter is a synced trait linked to its slider in the browser).
import { drawStackCheck } from "./stack_check.js";

// The scene drawers by demo name (the scene's "kind"); a new browser-drawn demo adds its own here.
const SCENES = { stack_check: drawStackCheck };

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
    const params = {};
    for (const name of scene.params) params[name] = model.get(name);
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.clearRect(0, 0, canvas.width, canvas.height);
    ctx.setTransform(canvas.width / scene.width, 0, 0, canvas.height / scene.height, 0, 0);
    const k = scene.backgroundScale || 1; // drawn at its own size: the figure's height may end in half a pixel
    ctx.drawImage(background, 0, 0, background.naturalWidth / k, background.naturalHeight / k);
    SCENES[scene.kind](ctx, scene, params);
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
      model.on(`change:${name}`, draw);
      listening.add(name);
    }
  };
  model.on("change:scene", load);
  model.on("change:alt", () => canvas.setAttribute("aria-label", model.get("alt") || ""));
  load();
}

export default { render };
