// The page's renderer, in a Web Worker so that the page never waits for
// it: the session core compiled to WebAssembly (web/src/lib.rs), given the
// compiled module by the page. Each request runs to its end; the page
// abandons one it no longer needs by ending this worker and starting
// another (the module is compiled once, so that is quick).

import { initSync, Playground, Settings } from "rayrepl-web";
import { replyOf } from "./replies.js";

/** The playground of the last scene, its text and settings, to pick its pixels. */
let current = null;

function settingsOf({ width, height, depth, samples, time }) {
  const settings = new Settings();
  Object.assign(settings, { width, height, depth, samples, time });
  return settings;
}

/** A playground with `settings`, or the refusal of a setting as a reply. */
function playground(settings) {
  const wasm = settingsOf(settings);
  try {
    return { playground: new Playground(wasm) };
  } catch (error) {
    return { refused: { end: "failed", outputs: [{ kind: "text", role: "error", text: String(error.message ?? error) }], images: [] } };
  } finally {
    wasm.free();
  }
}

/** Loads `scene` into a new playground with `settings` and renders it. */
function render(scene, settings) {
  current?.playground.free();
  current = null;
  const made = playground(settings);
  if (made.refused) return made.refused;
  const loaded = replyOf(made.playground.load("scene.ray", scene));
  current = { playground: made.playground, scene, settings: JSON.stringify(settings) };
  if (loaded.end !== "done") return loaded;
  const rendered = replyOf(current.playground.run(":render"));
  return { ...rendered, outputs: [...loaded.outputs, ...rendered.outputs] };
}

/** Runs `cell` (a command) in the playground of `scene`, rendering it first if this worker has not. */
function runOn(scene, settings, cell) {
  if (!current || current.scene !== scene || current.settings !== JSON.stringify(settings)) {
    const rendered = render(scene, settings);
    if (rendered.end !== "done") return rendered;
  }
  return replyOf(current.playground.run(cell));
}

/** The lesson's own session: `:lesson N`, then the learner's scene at each edit. */
let lesson = null;

function lessonCell(request) {
  if (request.start !== undefined) {
    lesson?.free();
    const made = playground(request.settings);
    if (made.refused) return made.refused;
    lesson = made.playground;
    return replyOf(lesson.run(`:lesson ${request.start}`));
  }
  if (!lesson) return { end: "failed", outputs: [{ kind: "text", role: "error", text: "no lesson started" }], images: [] };
  return replyOf(lesson.run(request.cell));
}

const handlers = {
  render: (request) => render(request.scene, request.settings),
  run: (request) => runOn(request.scene, request.settings, request.cell),
  lesson: lessonCell,
};

self.onmessage = ({ data }) => {
  if (data.kind === "init") {
    initSync({ module: data.module });
    self.postMessage({ kind: "ready" });
    return;
  }
  const started = performance.now();
  const reply = handlers[data.kind](data);
  const transfer = reply.images.flatMap((image) => [image.rgba.buffer, image.png.buffer]);
  self.postMessage({ id: data.id, took: performance.now() - started, ...reply }, transfer);
};
