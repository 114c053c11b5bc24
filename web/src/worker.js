// The page's renderer, in a Web Worker so that the page never waits for
// it: the session core compiled to WebAssembly (web/src/lib.rs), given the
// compiled module by the page. Each request runs to its end; the page
// abandons one it no longer needs by ending this worker and starting
// another (the module is compiled once, so that is quick).

import { initSync, Playground, Settings, png_of_rgba } from "rayrepl-web";
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

/** Loads `scene` into a new playground with `settings` and renders it,
 * or, given its `picture` (`{ width, height, rgba }`, put together from
 * the bands), takes that as its last picture. */
function render(scene, settings, picture) {
  current?.playground.free();
  current = null;
  const made = playground(settings);
  if (made.refused) return made.refused;
  const loaded = replyOf(made.playground.load("scene.ray", scene));
  current = { playground: made.playground, scene, settings: JSON.stringify(settings) };
  if (loaded.end !== "done") return loaded;
  if (picture) {
    current.playground.adopt_picture(picture.width, picture.height, picture.rgba);
    return loaded;
  }
  const rendered = replyOf(current.playground.run(":render"));
  return { ...rendered, outputs: [...loaded.outputs, ...rendered.outputs] };
}

/** Rows `top..bottom` of the picture of `scene` with `settings`, as RGBA
 * bytes (`band`): this worker's band of a picture that several workers
 * render, each in a playground of its own loaded with the same text. */
function band({ scene, settings, top, bottom }) {
  const made = playground(settings);
  if (made.refused) return made.refused;
  try {
    const loaded = replyOf(made.playground.load("scene.ray", scene));
    if (loaded.end !== "done") return loaded;
    const rendered = replyOf(made.playground.render_rows(top, bottom));
    return { ...rendered, outputs: [...loaded.outputs, ...rendered.outputs] };
  } finally {
    made.playground.free();
  }
}

/** Runs `cell` (a command) in the playground of `scene`, rendering it
 * first if this worker has not (unless the request brings its `picture`). */
function runOn({ scene, settings, cell, picture }) {
  if (!current || current.scene !== scene || current.settings !== JSON.stringify(settings)) {
    const rendered = render(scene, settings, picture);
    if (rendered.end !== "done") return rendered;
  }
  return replyOf(current.playground.run(cell));
}

/** The lesson's own session and its number: `:lesson N`, then the learner's scene at each edit. */
let lesson = null;

/** Starts lesson `number` unless this worker follows it already (a new worker follows none). */
function follow(number, settings) {
  if (lesson?.number === number) return null;
  lesson?.playground.free();
  lesson = null;
  const made = playground(settings);
  if (made.refused) return made.refused;
  lesson = { number, playground: made.playground };
  const started = replyOf(lesson.playground.run(`:lesson ${number}`));
  return { ...started, startingScene: listedScene(replyOf(lesson.playground.run(":list"))) };
}

/** The program `:list` lists, without the names of its inputs: the
 * listing gives each input as `<name>:LINE  text`, its next lines
 * indented under the text. */
function listedScene(reply) {
  const lines = [];
  let indent = 0;
  for (const output of reply.outputs.filter((output) => output.kind === "text" && output.role === "message")) {
    for (const line of output.text.split("\n")) {
      const named = /^<[^>]*>:\d+ +/.exec(line);
      if (named) indent = named[0].length;
      lines.push(named ? line.slice(indent) : line.slice(Math.min(indent, line.length - line.trimStart().length)));
    }
  }
  return lines.length ? `${lines.join("\n")}\n` : "";
}

/** Lesson `number`'s step, or, with `scene`, the verdict on it: the
 * scene run in place of the last one and checked once, as the terminal
 * checks an input (its lines are the editor's). */
function lessonCell({ number, settings, scene }) {
  const started = follow(number, settings);
  if (scene === undefined || started?.end === "failed") return started ?? { end: "done", outputs: [], images: [] };
  const checked = replyOf(lesson.playground.run_scene(scene));
  return started ? { ...checked, outputs: [...started.outputs, ...checked.outputs] } : checked;
}

const handlers = {
  run: runOn,
  lesson: lessonCell,
  band,
  png: ({ width, height, rgba }) => ({ end: "done", outputs: [], images: [], png: png_of_rgba(width, height, rgba) }),
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
  for (const bytes of [reply.animation, reply.band, reply.png]) if (bytes) transfer.push(bytes.buffer);
  self.postMessage({ id: data.id, took: performance.now() - started, ...reply }, transfer);
};
