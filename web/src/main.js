// The playground page: the editor, the picture, the controls, the
// diagnostics, the explanations of pixels, the lessons and the share
// links. What the session core does runs in a worker (worker.js); this
// file shows its outputs. The hooks of `window.rayrepl` are the guide's
// (docs/guide/playground.md).

import { defaultKeymap, history as undoHistory, historyKeymap, indentWithTab } from "@codemirror/commands";
import { setDiagnostics, lintGutter } from "@codemirror/lint";
import { EditorState } from "@codemirror/state";
import { EditorView, keymap, lineNumbers, highlightActiveLine } from "@codemirror/view";
import { ray, rayColours, readsTime } from "./highlight.js";
import { fragmentOf, readFragment } from "./link.js";
import { Renderer } from "./renderer.js";
import examples from "rayrepl-examples";

/** How long the page waits after a keystroke before rendering. */
const TYPING_PAUSE_MS = 300;
/** How long the page waits after a keystroke before checking the lesson's
 * step: each check of a scene that runs is a try, as an input typed at the
 * terminal is (wrong ones bring the example), so a check waits for the
 * learner to stop typing, not for a pause between two words. */
const LESSON_PAUSE_MS = 1200;
/** The time slider's range: the frames of `:anim 100`. */
const MOST_TIME = 100;
/** Frames of the animation that the play button plays (`:play FRAMES FPS`): the session's two seconds. */
const PLAYED_FRAMES = 24;
const PLAYED_FPS = 12;

const $ = (selector) => document.querySelector(selector);
const canvas = $("#picture");
const diagnosticsList = $("#diagnostics");
const status = $("#status");

/** The render settings, as the controls show them. */
const settings = { width: 640, height: 480, depth: 5, samples: 1, time: 0 };
const controls = ["width", "height", "depth", "samples", "time"];

// Workers from one compiled module: those of pictures (a new render
// abandons the ones running), each rendering a band of rows of the
// picture (the first also picks pixels and plays), and the lesson's
// session (its checks wait their turn; it also writes PNG files).
// (Compiled from its bytes, whatever type the server gives the file.)
const module = fetch(new URL("rayrepl_web_bg.wasm", import.meta.url))
  .then((response) => response.arrayBuffer())
  .then((bytes) => WebAssembly.compile(bytes));
const workerUrl = new URL("worker.js", import.meta.url);
/** Workers rendering the bands of a picture: one a core, at most 8, or
 * the `workers` of the page's query (`?workers=1`, to compare). */
const bandWorkers = Math.min(Math.max(Number(new URLSearchParams(location.search).get("workers")) || navigator.hardwareConcurrency || 1, 1), 8);
const renderers = Array.from({ length: bandWorkers }, () => new Renderer(module, workerUrl, { supersede: true }));
const renderer = renderers[0];
const tutor = new Renderer(module, workerUrl, { supersede: false });

/** The scene of the picture shown, to pick its pixels. */
let shown = null;
/** The picture shown (`{ width, height, rgba }`), for its PNG file. */
let shownPicture = null;
/** The APNG file of the animation last played, for its download. */
let shownAnimation = null;

// The editor.
const renderSoon = debounce(render, TYPING_PAUSE_MS);
const checkLessonSoon = debounce(checkLesson, LESSON_PAUSE_MS);
const editor = new EditorView({
  parent: $("#editor"),
  state: EditorState.create({
    doc: examples.scenarios.find((example) => example.name === "hello")?.text ?? "",
    extensions: [
      lineNumbers(),
      undoHistory(),
      highlightActiveLine(),
      lintGutter(),
      ray,
      rayColours,
      keymap.of([...defaultKeymap, ...historyKeymap, indentWithTab]),
      EditorView.updateListener.of((update) => {
        if (update.docChanged) {
          renderSoon();
          checkLessonSoon();
        }
      }),
    ],
  }),
});

function sceneText() {
  return editor.state.doc.toString();
}

/** Puts `text` in the editor as typing would: the picture follows. */
function load(text) {
  editor.dispatch({
    changes: { from: 0, to: editor.state.doc.length, insert: text },
    userEvent: "input.paste",
  });
}

function debounce(work, pause) {
  let timer = null;
  return () => {
    clearTimeout(timer);
    timer = setTimeout(work, pause);
  };
}

// What the worker's replies show.

function setState(state, message) {
  canvas.dataset.state = state;
  if (message !== undefined) status.textContent = message;
}

/** Each diagnostic in its element under the editor, with its line, and marked in the editor. */
function showDiagnostics(outputs) {
  const diagnostics = outputs.filter((output) => output.kind === "diagnostic");
  diagnosticsList.replaceChildren(
    ...diagnostics.map(({ rendered, data }) => {
      const element = document.createElement("pre");
      element.className = `diagnostic ${data.severity}`;
      element.dataset.line = data.place.line;
      element.dataset.code = data.code;
      element.textContent = rendered;
      element.addEventListener("click", () => goTo(data.place));
      return element;
    }),
  );
  const doc = editor.state.doc;
  const offset = (line, column) => {
    const at = doc.line(Math.min(Math.max(line, 1), doc.lines));
    return Math.min(at.from + column - 1, at.to);
  };
  const marks = diagnostics
    .filter(({ data }) => data.place.source === "scene.ray")
    .map(({ data }) => {
      const { line, column_utf16, end_line, end_column_utf16 } = data.place;
      const from = offset(line, column_utf16);
      const help = data.help.map((help) => `help: ${help.message}`);
      return {
        from,
        to: Math.max(from, offset(end_line, end_column_utf16)),
        severity: data.severity,
        message: [data.message, ...data.notes.map((note) => `note: ${note}`), ...help].join("\n"),
      };
    });
  editor.dispatch(setDiagnostics(editor.state, marks));
}

function goTo(place) {
  if (place.source !== "scene.ray") return;
  const line = editor.state.doc.line(Math.min(place.line, editor.state.doc.lines));
  editor.dispatch({ selection: { anchor: Math.min(line.from + place.column_utf16 - 1, line.to) }, scrollIntoView: true });
  editor.focus();
}

/** The texts of a reply (messages, notes, printed lines), stripped of terminal styles. */
function textsOf(outputs) {
  return outputs
    .filter((output) => output.kind === "text")
    .map(({ role, text }) => ({ role, text: text.replace(/\x1b\[[0-9;]*m/g, "") }));
}

function showMessages(outputs) {
  $("#messages").replaceChildren(
    ...textsOf(outputs).map(({ role, text }) => {
      const element = document.createElement("div");
      element.className = `message ${role}`;
      element.textContent = text;
      return element;
    }),
  );
}

function paint(image) {
  canvas.width = image.width;
  canvas.height = image.height;
  const pixels = new ImageData(new Uint8ClampedArray(image.rgba.buffer, image.rgba.byteOffset, image.rgba.length), image.width, image.height);
  canvas.getContext("2d").putImageData(pixels, 0, 0);
}

/** The bands of the workers' `replies`, top to bottom, as one picture. */
function stitch(width, height, replies) {
  const rgba = new Uint8Array(width * height * 4);
  let offset = 0;
  for (const { band } of replies) {
    rgba.set(band, offset);
    offset += band.length;
  }
  return { width, height, rgba };
}

// Rendering.

async function render() {
  stopPlaying();
  const scene = sceneText();
  const asked = { ...settings };
  $("#time-controls").hidden = !readsTime(scene);
  setState("rendering", "rendering…");
  const started = performance.now();
  // Band k of n is rows [k h / n, (k + 1) h / n): every pixel is computed
  // on its own, so the bands put together are the bytes of one render.
  const edge = (k) => Math.round((k * asked.height) / renderers.length);
  const replies = await Promise.all(
    renderers.map((worker, k) => worker.request({ kind: "band", scene, settings: asked, top: edge(k), bottom: edge(k + 1) })),
  );
  if (replies.some((reply) => reply.superseded)) return;
  const reply = replies.find((reply) => reply.end !== "done") ?? replies[0];
  showDiagnostics(reply.outputs);
  showMessages(reply.outputs);
  if (reply.end !== "done") {
    // The last good picture stays; a setting refused says why.
    const refused = textsOf(reply.outputs).find(({ role }) => role === "error");
    setState("error", reply.stopped ?? refused?.text ?? "the scene has an error: the picture is the last one that rendered");
    return;
  }
  const image = stitch(asked.width, asked.height, replies);
  paint(image);
  $("#mark").hidden = true;
  shown = { scene, settings: asked };
  shownPicture = image;
  const workers = renderers.length === 1 ? "" : ` (${renderers.length} workers)`;
  setState("done", `${image.width}×${image.height} in ${Math.round(performance.now() - started)} ms${workers}`);
}

/** Why pixel (x, y) of the picture shown has its colour (`:pick X Y`). */
async function pick(x, y) {
  if (!shown) return;
  const explanation = $("#explanation");
  explanation.textContent = `why pixel (${x}, ${y})…`;
  // With the picture the bands made: the worker need not render it again.
  const reply = await renderer.request({ kind: "run", ...shown, cell: `:pick ${x} ${y}`, picture: shownPicture });
  if (reply.superseded) return;
  resumeRendering();
  const found = reply.outputs.find((output) => output.kind === "explanation");
  markPixel(x, y);
  explanation.dataset.pixel = `${x},${y}`;
  explanation.textContent = found ? found.text : textsOf(reply.outputs).map(({ text }) => text).join("\n") || reply.stopped || "";
}

/** Renders again if a pick abandoned the render of the editor's scene. */
function resumeRendering() {
  if (canvas.dataset.state === "rendering") renderSoon();
}

/** Marks pixel (x, y) over the picture, at its place as the picture is shown. */
function markPixel(x, y) {
  const mark = $("#mark");
  mark.style.left = `${canvas.clientLeft + ((x + 0.5) * canvas.clientWidth) / canvas.width}px`;
  mark.style.top = `${canvas.clientTop + ((y + 0.5) * canvas.clientHeight) / canvas.height}px`;
  mark.hidden = false;
}

canvas.addEventListener("click", (event) => {
  // From inside the border, where the pixels are drawn (offsetX is rounded).
  const box = canvas.getBoundingClientRect();
  const x = Math.floor(((event.clientX - box.left - canvas.clientLeft) * canvas.width) / canvas.clientWidth);
  const y = Math.floor(((event.clientY - box.top - canvas.clientTop) * canvas.height) / canvas.clientHeight);
  pick(Math.min(Math.max(x, 0), canvas.width - 1), Math.min(Math.max(y, 0), canvas.height - 1));
});

$("#stop").addEventListener("click", () => {
  const reason = "stopped: the work was abandoned (its worker ended and started again)";
  for (const worker of renderers) worker.stop(reason);
  tutor.stop(reason);
  stopPlaying();
});

// The controls.

function showSettings() {
  for (const name of controls) $(`#${name}`).value = settings[name];
  $("#time-value").textContent = settings.time;
}

function changeSettings(changed) {
  for (const name of controls) {
    if (changed[name] === undefined) continue;
    const value = Number(changed[name]);
    if (Number.isFinite(value)) settings[name] = value;
  }
  showSettings();
  renderSoon();
}

for (const name of controls) {
  $(`#${name}`).addEventListener("input", (event) => changeSettings({ [name]: event.target.value }));
}
$("#time").max = MOST_TIME;

// The play button: the frames of `:play`, rendered once, then shown in turn.
let playing = null;

function stopPlaying() {
  clearInterval(playing);
  playing = null;
  $("#play").textContent = "▶ play";
}

$("#play").addEventListener("click", async () => {
  if (playing) return stopPlaying();
  setState("rendering", `rendering ${PLAYED_FRAMES} frames…`);
  const reply = await renderer.request({
    kind: "run",
    scene: sceneText(),
    settings: { ...settings },
    cell: `:play ${PLAYED_FRAMES} ${PLAYED_FPS}`,
  });
  if (reply.superseded) return;
  const frames = reply.outputs.find((output) => output.kind === "frames");
  if (!frames) {
    showMessages(reply.outputs);
    setState("error", reply.stopped ?? "the animation did not render");
    return;
  }
  setState("done", `${frames.frames.length} frames in ${Math.round(reply.took)} ms`);
  shownAnimation = reply.animation;
  $("#download-animation").hidden = false;
  let frame = 0;
  $("#play").textContent = "■ pause";
  playing = setInterval(() => {
    paint(reply.images[frames.frames[frame].index]);
    frame = (frame + 1) % frames.frames.length;
  }, 1000 / frames.fps);
});

// Examples, download, share.

$("#examples").append(
  ...examples.scenarios.map(({ name }) => {
    const option = document.createElement("option");
    option.value = option.textContent = name;
    return option;
  }),
);
$("#examples").addEventListener("change", (event) => {
  const example = examples.scenarios.find(({ name }) => name === event.target.value);
  if (example) load(example.text);
});

function download(bytes, name, type) {
  const link = document.createElement("a");
  link.href = URL.createObjectURL(new Blob([bytes], { type }));
  link.download = name;
  link.click();
  setTimeout(() => URL.revokeObjectURL(link.href), 1000);
}

$("#download").addEventListener("click", async () => {
  const picture = shownPicture;
  if (!picture) return;
  // Written by the lesson's worker, which a render never abandons; a
  // lesson's check that comes while it waits takes its turn: ask again.
  let reply;
  do reply = await tutor.request({ kind: "png", ...picture, rgba: picture.rgba.slice() });
  while (reply.superseded);
  if (reply.png) download(reply.png, "scene.png", "image/png");
});
$("#download-animation").addEventListener("click", () => {
  if (shownAnimation) download(shownAnimation, "scene.apng", "image/apng");
});

async function link() {
  const fragment = await fragmentOf(sceneText(), settings);
  return `${location.origin}${location.pathname}${fragment}`;
}

$("#share").addEventListener("click", async () => {
  const shareStatus = $("#share-status");
  try {
    const made = await link();
    history.replaceState(null, "", made);
    await navigator.clipboard?.writeText(made).catch(() => {});
    shareStatus.textContent = "the link is in the address bar (and copied)";
    delete shareStatus.dataset.error;
  } catch (error) {
    shareStatus.textContent = error.message;
    shareStatus.dataset.error = "true";
  }
});

/** Opens the scene of the page's link, if it has one; says what is wrong with a damaged one. */
async function openLink() {
  try {
    const shared = await readFragment(location.hash);
    if (!shared) return false;
    changeSettings(shared.settings);
    load(shared.scene);
    return true;
  } catch (error) {
    $("#share-status").textContent = error.message;
    $("#share-status").dataset.error = "true";
    return false;
  }
}

window.addEventListener("hashchange", openLink);

// Lessons: `:lesson N` in a session of their own; when the learner stops
// typing, the scene is run there in place of the last one and checked once.

const lessonPanel = $("#lesson");
let lessonNumber = null;

$("#lessons").append(
  ...examples.lessons.map(({ number, title }) => {
    const option = document.createElement("option");
    option.value = number;
    option.textContent = `${number}. ${title}`;
    return option;
  }),
);

$("#lessons").addEventListener("change", async (event) => {
  lessonNumber = event.target.value || null;
  lessonPanel.hidden = !lessonNumber;
  if (!lessonNumber) return;
  const started = await tutor.request({ kind: "lesson", number: lessonNumber, settings: { ...settings } });
  showLesson(started);
  // The lesson's starting scene in the editor, as the session holds it: the picture and the check follow.
  if (started.startingScene !== undefined) load(started.startingScene);
});

function showLesson(reply) {
  if (reply.superseded) return;
  const step = reply.outputs.findLast((output) => output.kind === "lesson-step");
  if (step) $("#lesson-task").textContent = step.text;
  const verdict = reply.outputs.findLast((output) => output.kind === "lesson-verdict");
  const verdictElement = $("#lesson-verdict");
  verdictElement.textContent = verdict ? verdict.text : "";
  verdictElement.dataset.done = verdict ? verdict.done : "";
  const pictures = reply.outputs.findLast((output) => output.kind === "lesson-pictures");
  if (pictures) {
    const image = reply.images[pictures.image.index];
    const goal = $("#lesson-pictures");
    goal.width = image.width;
    goal.height = image.height;
    goal.getContext("2d").putImageData(new ImageData(new Uint8ClampedArray(image.rgba.buffer), image.width, image.height), 0, 0);
  }
  const errors = textsOf(reply.outputs).filter(({ role }) => role === "error");
  if (errors.length) verdictElement.textContent = errors.map(({ text }) => text).join("\n");
}

async function checkLesson() {
  if (!lessonNumber) return;
  const reply = await tutor.request({ kind: "lesson", number: lessonNumber, settings: { ...settings }, scene: sceneText() });
  showLesson(reply);
}

// The hooks for tests and other pages (docs/guide/playground.md).
window.rayrepl = {
  load,
  link,
  settings: changeSettings,
};

showSettings();
renderer.ready.then(async () => {
  if (!(await openLink())) render();
});
