// The same bytes in Node: every bundled scenario, every golden scene and
// the unseen scenes of scenes.mjs rendered by the WebAssembly build of the
// session core (the module web/build.sh makes) and by the native binary
// at the same settings, their PNG files compared byte for byte.
//
//   node --test web/test/node.mjs     (after web/build.sh and cargo build --release)

import assert from "node:assert/strict";
import { spawnSync } from "node:child_process";
import { mkdtempSync, readFileSync, readdirSync, writeFileSync } from "node:fs";
import { tmpdir } from "node:os";
import { join } from "node:path";
import { test } from "node:test";
import { pathToFileURL } from "node:url";
import { replyOf } from "../src/replies.js";
import { unseenScenes } from "./scenes.mjs";

const root = join(import.meta.dirname, "../..");
const pkg = process.env.RAYREPL_WEB_PKG ?? join(root, "target/web/pkg");
const native = process.env.RAYREPL_BIN ?? join(root, "target/release/rayrepl");
const glue = await import(pathToFileURL(join(pkg, "rayrepl_web.js")));
glue.initSync({ module: readFileSync(join(pkg, "rayrepl_web_bg.wasm")) });
const scratch = mkdtempSync(join(tmpdir(), "rayrepl-web-"));

/** The golden scenes' settings: tests/suite/golden.rs renders every scenario at 96x72, time 7. */
const GOLDEN = { width: 96, height: 72, depth: 5, samples: 1, time: 7 };
/** The bundled scenarios as the page shows them first (its default size), at time 0. */
const PAGE = { width: 320, height: 240, depth: 5, samples: 1, time: 0 };

/** The PNG file of `text` rendered in the WebAssembly build with `settings`. */
function renderInWasm(text, settings) {
  const wasmSettings = Object.assign(new glue.Settings(), settings);
  const playground = new glue.Playground(wasmSettings);
  try {
    const loaded = replyOf(playground.load("scene.ray", text));
    assert.equal(loaded.end, "done", JSON.stringify(loaded.outputs));
    const rendered = replyOf(playground.run(":render"));
    assert.equal(rendered.end, "done", JSON.stringify(rendered.outputs));
    const picture = rendered.outputs.find((output) => output.kind === "picture");
    assert.ok(picture, "the render shows a picture");
    return Buffer.from(rendered.images[picture.image.index].png);
  } finally {
    playground.free();
  }
}

/** The PNG file of `text` rendered in bands, as the page's workers
 * render them: rows [edge k, edge k + 1) each in a playground of its own,
 * put together and written by `png_of_rgba`. The edges fall inside the
 * renderer's bands of 16 rows, to show that no split changes a byte. */
function renderInWasmBands(text, settings) {
  const edges = [0, 1, 37, Math.floor(settings.height / 2) + 3, settings.height];
  const rgba = new Uint8Array(settings.width * settings.height * 4);
  for (let k = 0; k + 1 < edges.length; k++) {
    const playground = new glue.Playground(Object.assign(new glue.Settings(), settings));
    try {
      const loaded = replyOf(playground.load("scene.ray", text));
      assert.equal(loaded.end, "done", JSON.stringify(loaded.outputs));
      const { end, outputs, band } = replyOf(playground.render_rows(edges[k], edges[k + 1]));
      assert.equal(end, "done", JSON.stringify(outputs));
      assert.equal(band.length, (edges[k + 1] - edges[k]) * settings.width * 4);
      rgba.set(band, edges[k] * settings.width * 4);
    } finally {
      playground.free();
    }
  }
  return Buffer.from(glue.png_of_rgba(settings.width, settings.height, rgba));
}

/** The PNG file the native binary writes for the scene file `path` with `settings`. */
function renderNatively(path, { width, height, depth, samples, time }, name) {
  const out = join(scratch, `${name}.png`);
  const args = [path, "--width", width, "--height", height, "--depth", depth, "--samples", samples, "--time", time, "-o", out];
  const run = spawnSync(native, args.map(String), { encoding: "utf8" });
  assert.equal(run.status, 0, `${native} ${args.join(" ")}: ${run.stderr}`);
  return readFileSync(out);
}

function sameBytes(name, path, text, settings) {
  const wasm = renderInWasm(text, settings);
  const expected = renderNatively(path, settings, name);
  assert.ok(wasm.equals(expected), `${name}: the WebAssembly build's PNG (${wasm.length} bytes) differs from the native one (${expected.length} bytes)`);
}

const scenarios = readdirSync(join(root, "scenarios")).filter((file) => file.endsWith(".ray")).sort();
const goldens = readdirSync(join(root, "tests/golden")).filter((file) => file.endsWith(".png")).sort();

test("there are scenarios and golden scenes to compare", () => {
  assert.ok(scenarios.length >= 8);
  assert.equal(goldens.length, scenarios.length);
});

for (const file of scenarios) {
  test(`scenario ${file} at ${PAGE.width}x${PAGE.height} gives the native bytes`, () => {
    const path = join(root, "scenarios", file);
    sameBytes(`page-${file}`, path, readFileSync(path, "utf8"), PAGE);
  });
}

for (const golden of goldens) {
  const file = golden.replace(/\.png$/, ".ray");
  test(`golden scene ${file} (96x72, time 7) gives the native bytes`, () => {
    const path = join(root, "scenarios", file);
    sameBytes(`golden-${file}`, path, readFileSync(path, "utf8"), GOLDEN);
  });
}

for (const scene of unseenScenes) {
  test(`unseen scene ${scene.name} gives the native bytes`, () => {
    const path = join(scratch, `${scene.name}.ray`);
    writeFileSync(path, scene.text);
    sameBytes(`unseen-${scene.name}`, path, scene.text, scene.settings);
  });
}

for (const { name, text, settings } of [
  ...scenarios.map((file) => ({ name: file, text: readFileSync(join(root, "scenarios", file), "utf8"), settings: PAGE })),
  ...unseenScenes,
]) {
  test(`${name} rendered in bands, put together, gives the native bytes`, () => {
    writeFileSync(join(scratch, `bands-${name}`), text);
    const bands = renderInWasmBands(text, settings);
    const expected = renderNatively(join(scratch, `bands-${name}`), settings, `bands-${name}`);
    assert.ok(bands.equals(expected), `${name}: the bands' PNG (${bands.length} bytes) differs from the native one (${expected.length} bytes)`);
  });
}

test("a scene that does not parse gives its diagnostic with its line", () => {
  const playground = new glue.Playground(Object.assign(new glue.Settings(), PAGE));
  try {
    const loaded = replyOf(playground.load("scene.ray", "camera distance 8 angle 1 end\nput sphere radius end\n"));
    assert.equal(loaded.end, "failed");
    const diagnostic = loaded.outputs.find((output) => output.kind === "diagnostic");
    assert.ok(diagnostic, JSON.stringify(loaded.outputs));
    assert.equal(diagnostic.data.place.line, 2);
    assert.match(diagnostic.rendered, /scene\.ray:2:/);
  } finally {
    playground.free();
  }
});

test("a band's reply gives the notes :render gives", () => {
  const playground = new glue.Playground(Object.assign(new glue.Settings(), PAGE));
  try {
    assert.equal(replyOf(playground.load("scene.ray", "camera distance 8 angle 1 end\nput sphere center 0, 0, 0 radius 1 kd 1 ks 0 phong 1 color 9, 9, 9 end\n")).end, "done");
    const notes = (reply) => reply.outputs.filter((output) => output.kind === "text" && output.role === "note").map((output) => output.text);
    const band = replyOf(playground.render_rows(0, 16));
    const rendered = replyOf(playground.run(":render"));
    assert.deepEqual(notes(band), notes(rendered));
    assert.match(notes(band).join("\n"), /default ambient light.*\n.*no light yet/);
  } finally {
    playground.free();
  }
});

test(":pick of a picture put together from bands explains the pixel as after :render", () => {
  const text = readFileSync(join(root, "scenarios/solar.ray"), "utf8");
  const settings = { width: 64, height: 48, depth: 5, samples: 1, time: 0 };
  const explained = (prepare) => {
    const playground = new glue.Playground(Object.assign(new glue.Settings(), settings));
    try {
      assert.equal(replyOf(playground.load("scene.ray", text)).end, "done");
      prepare(playground);
      const picked = replyOf(playground.run(":pick 31 20"));
      assert.equal(picked.end, "done", JSON.stringify(picked.outputs));
      return picked.outputs.filter((output) => output.kind !== "picture");
    } finally {
      playground.free();
    }
  };
  const rendered = explained((playground) => replyOf(playground.run(":render")));
  const adopted = explained((playground) => {
    const { band } = replyOf(playground.render_rows(0, settings.height));
    playground.adopt_picture(settings.width, settings.height, band);
  });
  assert.ok(rendered.some((output) => output.kind === "explanation"), JSON.stringify(rendered));
  assert.deepEqual(adopted, rendered);
});

test("the frames :play shows, as an APNG file, are the bytes of --anim", () => {
  const path = join(root, "scenarios/spiral.ray");
  const settings = { width: 64, height: 48, depth: 5, samples: 1, time: 0 };
  const playground = new glue.Playground(Object.assign(new glue.Settings(), settings));
  try {
    assert.equal(replyOf(playground.load("scene.ray", readFileSync(path, "utf8"))).end, "done");
    const played = replyOf(playground.run(":play 4 12"));
    assert.equal(played.end, "done", JSON.stringify(played.outputs));
    const out = join(scratch, "spiral.apng");
    const args = [path, "--width", "64", "--height", "48", "--anim", "4", "--fps", "12", "-q", "-o", out];
    const run = spawnSync(native, args, { encoding: "utf8" });
    assert.equal(run.status, 0, run.stderr);
    assert.ok(Buffer.from(played.animation).equals(readFileSync(out)), "the APNG files differ");
  } finally {
    playground.free();
  }
});
