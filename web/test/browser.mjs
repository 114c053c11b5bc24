// The playground in a real browser: Debian's Chromium driven by
// playwright-core (never a browser it downloads), the page of web/dist/
// served on 127.0.0.1. Every picture is compared byte for byte with what
// the native binary renders for the same scene and settings; messages and
// explanations with what it prints.
//
//   RAYREPL_CHROMIUM=/usr/bin/chromium node --test web/test/browser.mjs   (after web/build.sh)

import assert from "node:assert/strict";
import { spawnSync } from "node:child_process";
import { existsSync, mkdirSync, mkdtempSync, readFileSync, readdirSync, writeFileSync } from "node:fs";
import { tmpdir } from "node:os";
import { join } from "node:path";
import { after, before, test } from "node:test";
import { unseenScenes } from "./scenes.mjs";
import { launchBrowser, serve } from "./serve.mjs";

const root = join(import.meta.dirname, "../..");
const dist = join(root, "web/dist");
const native = process.env.RAYREPL_BIN ?? join(root, "target/release/rayrepl");
const scratch = mkdtempSync(join(tmpdir(), "rayrepl-browser-"));
/** The page's first settings (web/src/main.js). */
const PAGE = { width: 640, height: 480, depth: 5, samples: 1, time: 0 };
/** The golden scenes' settings (tests/suite/golden.rs). */
const GOLDEN = { width: 96, height: 72, depth: 5, samples: 1, time: 7 };
/** The bundled scenarios at a size quick to render twenty times. */
const SMALL = { width: 160, height: 120, depth: 5, samples: 1, time: 0 };

let server;
let browser;
let base;

before(async () => {
  assert.ok(existsSync(join(dist, "index.html")), "web/dist/ is built (bash web/build.sh)");
  server = await serve(dist);
  base = server.base;
  browser = await launchBrowser();
});

after(async () => {
  await browser?.close();
  server?.close();
});

/** Runs the native binary in the scratch folder (so that it names the scene `scene.ray`, as the page does). */
function runNative(args) {
  const run = spawnSync(native, args.map(String), { cwd: scratch, encoding: "utf8" });
  return run;
}

/** `text` written as scratch/scene.ray. */
function sceneFile(text) {
  writeFileSync(join(scratch, "scene.ray"), text);
  return "scene.ray";
}

function settingsArgs({ width, height, depth, samples, time }) {
  return ["--width", width, "--height", height, "--depth", depth, "--samples", samples, "--time", time];
}

/** The RGB bytes the native binary renders for `text` with `settings` (its PPM file, less the header). */
function nativePixels(text, settings) {
  const run = runNative([sceneFile(text), ...settingsArgs(settings), "-q", "-o", "out.ppm"]);
  assert.equal(run.status, 0, run.stderr);
  const ppm = readFileSync(join(scratch, "out.ppm"));
  const header = `P6\n${settings.width} ${settings.height}\n255\n`;
  assert.equal(ppm.subarray(0, header.length).toString("latin1"), header);
  return ppm.subarray(header.length);
}

/** A new page of the playground, opened at `fragment`, its first picture waited for. */
async function openPage(fragment = "") {
  // Wide enough for the picture at its size: a pixel clicked is a pixel of the canvas.
  const page = await browser.newPage({ viewport: { width: 1600, height: 1000 } });
  const problems = [];
  page.on("pageerror", (error) => problems.push(String(error)));
  await page.goto(`${base}${fragment}`);
  await page.waitForFunction(() => window.rayrepl && document.querySelector("#picture").dataset.state !== "rendering");
  page.problems = problems;
  return page;
}

/** The canvas's pixels as RGB bytes, once it is `done` with `width` x `height` pixels equal to `expected` (or until the time is up). */
async function waitForPixels(page, expected, { width, height }) {
  const reading = await page
    .waitForFunction(
      ({ expected, width, height }) => {
        const canvas = document.querySelector("#picture");
        if (canvas.dataset.state !== "done" || canvas.width !== width || canvas.height !== height) return false;
        const rgba = canvas.getContext("2d").getImageData(0, 0, width, height).data;
        let rgb = "";
        for (let i = 0; i < rgba.length; i += 4) rgb += String.fromCharCode(rgba[i], rgba[i + 1], rgba[i + 2]);
        const base64 = btoa(rgb);
        return base64 === expected ? base64 : false;
      },
      { expected: Buffer.from(expected).toString("base64"), width, height },
      { timeout: 30_000, polling: 100 },
    )
    .catch(() => null);
  if (reading) return;
  const state = await page.evaluate(() => {
    const canvas = document.querySelector("#picture");
    return { state: canvas.dataset.state, width: canvas.width, height: canvas.height, status: document.querySelector("#status").textContent, diagnostics: document.querySelector("#diagnostics").textContent };
  });
  assert.fail(`the canvas never showed the native bytes: ${JSON.stringify(state)}`);
}

/** Puts `text` in the page's editor with `settings`, through the hooks, and checks the picture against the native bytes. */
async function checkScene(page, text, settings) {
  await page.evaluate(({ text, settings }) => {
    window.rayrepl.settings(settings);
    window.rayrepl.load(text);
  }, { text, settings });
  await waitForPixels(page, nativePixels(text, settings), settings);
}

const scenarios = readdirSync(join(root, "scenarios")).filter((file) => file.endsWith(".ray")).sort();
const HELLO = readFileSync(join(root, "scenarios/hello.ray"), "utf8");

test("the page opens with a first picture, the native bytes, within 2 s", async () => {
  const page = await browser.newPage();
  const started = Date.now();
  await page.goto(base);
  await page.waitForFunction(() => document.querySelector("#picture").dataset.state === "done", null, { timeout: 10_000 });
  const took = Date.now() - started;
  console.log(`first picture after ${took} ms`);
  assert.ok(took < 2000, `the first picture came after ${took} ms`);
  await waitForPixels(page, nativePixels(HELLO, PAGE), PAGE);
  mkdirSync(join(root, "target/web"), { recursive: true });
  await page.setViewportSize({ width: 1400, height: 900 });
  await page.screenshot({ path: join(root, "target/web/page.png") });
  await page.close();
});

test("three workers render the bands of a picture, put together to the native bytes", async () => {
  const page = await openPage("?workers=3");
  for (const [text, settings] of [[readFileSync(join(root, "scenarios/solar.ray"), "utf8"), PAGE], [unseenScenes[1].text, unseenScenes[1].settings]]) {
    await checkScene(page, text, settings);
    assert.match(await page.$eval("#status", (element) => element.textContent), /\(3 workers\)$/);
  }
  await page.close();
});

test("a scene typed into the editor renders to the native bytes", async () => {
  const page = await openPage();
  const typed = "camera distance 9 angle 0.9 end\nambient 0.25\nlight vector 0.4, 0, 0.6 intensity 0.8 end\n" +
    "put box center 0, 0, 0 length 2, 1, 1.5\nkd 0.7 ks 0.3 phong 30 color 30, 160, 220\nend\n";
  await page.click(".cm-content");
  await page.keyboard.press("Control+A");
  await page.keyboard.press("Delete");
  await page.keyboard.type(typed);
  const lines = await page.$$eval(".cm-line", (elements) => elements.map((element) => element.textContent));
  const text = lines.join("\n");
  assert.equal(text, typed, "the editor holds what was typed");
  await waitForPixels(page, nativePixels(typed, PAGE), PAGE);
  await page.close();
});

test("an error shows the terminal's diagnostic at its line, and the last picture stays", async () => {
  const page = await openPage();
  await waitForPixels(page, nativePixels(HELLO, PAGE), PAGE);
  await page.click(".cm-content");
  await page.keyboard.press("Control+End");
  await page.keyboard.type("\nput sphere radius 2 end\n");
  const broken = `${HELLO}\nput sphere radius 2 end\n`;
  await page.waitForSelector("#diagnostics [data-line]", { timeout: 10_000 });
  await page.waitForFunction(() => document.querySelector("#picture").dataset.state === "error");
  const shown = await page.$$eval("#diagnostics [data-line]", (elements) => elements.map((element) => ({ line: element.dataset.line, text: element.textContent })));
  const check = runNative(["--check", sceneFile(broken)]);
  assert.equal(check.status, 1);
  const line = String(broken.split("\n").indexOf("put sphere radius 2 end") + 1);
  assert.deepEqual(shown, [{ line, text: check.stderr }]);
  const marked = await page.$$eval(".cm-lintRange-error", (elements) => elements.length);
  assert.ok(marked >= 1, "the error is marked in the editor");
  // The canvas keeps the last good picture.
  const kept = await page.evaluate(() => document.querySelector("#picture").width);
  assert.equal(kept, PAGE.width);
  await page.close();
});

test("a click on a pixel explains it as --explain does", async () => {
  const page = await openPage();
  await waitForPixels(page, nativePixels(HELLO, PAGE), PAGE);
  const [x, y] = [320, 260];
  const box = await page.$eval("#picture", (canvas) => {
    const { left, top } = canvas.getBoundingClientRect();
    const scale = canvas.clientWidth / canvas.width;
    return { left: left + canvas.clientLeft, top: top + canvas.clientTop, scale };
  });
  await page.mouse.click(box.left + (x + 0.5) * box.scale, box.top + (y + 0.5) * box.scale);
  await page.waitForFunction((pixel) => document.querySelector("#explanation").dataset.pixel === pixel, `${x},${y}`);
  await page.waitForFunction(() => document.querySelector("#explanation").textContent.startsWith("pixel"));
  const explanation = await page.$eval("#explanation", (element) => element.textContent);
  const run = runNative([sceneFile(HELLO), ...settingsArgs(PAGE), "--explain", `${x},${y}`]);
  assert.equal(run.status, 0, run.stderr);
  assert.equal(explanation, run.stdout.trimEnd());
  await page.close();
});

test("a shared link opens the same scene and settings; a damaged or too long one says so", async () => {
  const page = await openPage();
  const scene = unseenScenes[0];
  await checkScene(page, scene.text, scene.settings);
  const link = await page.evaluate(() => window.rayrepl.link());
  assert.match(link, /#v=1&w=160&h=120&d=7&s=1&t=0&scene=[A-Za-z0-9_-]+$/);
  await page.click("#share");
  await page.waitForFunction(() => document.querySelector("#share-status").textContent.startsWith("the link is in the address bar"));
  assert.equal(page.url(), link, "the button puts the link in the address bar");
  await page.close();

  const opened = await openPage(link.slice(link.indexOf("#")));
  await waitForPixels(opened, nativePixels(scene.text, scene.settings), scene.settings);
  await opened.close();

  const damaged = await openPage("#v=1&w=160&h=120&d=5&s=1&t=0&scene=AAAA");
  assert.match(await damaged.$eval("#share-status", (element) => element.textContent), /this link is damaged/);
  await damaged.close();
  const long = await openPage(`#v=1&w=160&h=120&d=5&s=1&t=0&scene=${"A".repeat(40_000)}`);
  assert.match(await long.$eval("#share-status", (element) => element.textContent), /this link is too long/);
  await long.close();
});

test("scenes the project has never seen render to the native bytes", async () => {
  const page = await openPage();
  for (const scene of unseenScenes) await checkScene(page, scene.text, scene.settings);
  await page.close();
});

test("every bundled scenario renders to the native bytes, small and at the golden settings", async () => {
  const page = await openPage();
  for (const file of scenarios) {
    const text = readFileSync(join(root, "scenarios", file), "utf8");
    for (const settings of [SMALL, GOLDEN]) await checkScene(page, text, settings);
  }
  assert.deepEqual(page.problems, []);
  await page.close();
});

test("a render that runs too long is stopped, and the page goes on", async () => {
  const page = await openPage();
  const slow = readFileSync(join(root, "scenarios/menger.ray"), "utf8");
  await page.evaluate((text) => {
    window.rayrepl.settings({ width: 2000, height: 2000, depth: 10, samples: 64 });
    window.rayrepl.load(text);
  }, slow);
  await page.waitForFunction(() => document.querySelector("#picture").dataset.state === "rendering");
  await page.waitForTimeout(500);
  await page.click("#stop");
  await page.waitForFunction(() => document.querySelector("#picture").dataset.state === "error");
  assert.match(await page.$eval("#status", (element) => element.textContent), /stopped/);
  await checkScene(page, HELLO, SMALL);
  await page.close();
});

test("a runaway recursion ends with the terminal's diagnostic, and the page goes on", async () => {
  const page = await openPage();
  const runaway = "camera distance 8 angle 1 end\nambient 0.2\nproc f(n)\nf(n + 1)\nend\nf(0)\n";
  await page.evaluate((text) => window.rayrepl.load(text), runaway);
  await page.waitForSelector("#diagnostics [data-line]", { timeout: 30_000 });
  const shown = await page.$eval("#diagnostics [data-line]", (element) => element.textContent);
  // The browser's limit on calls is 1,000 (web/src/lib.rs): the command line's message at that limit.
  const check = runNative(["--check", "--max-calls", "1000", sceneFile(runaway)]);
  assert.equal(shown, check.stderr);
  await checkScene(page, HELLO, SMALL);
  await page.close();
});

test("a lesson shows its step, checks each edit and shows the goal beside the learner's picture", async () => {
  const page = await openPage();
  await page.selectOption("#lessons", "1");
  await page.waitForFunction(() => document.querySelector("#lesson-task").textContent.startsWith("step 1 of 3"));
  await page.evaluate(() => window.rayrepl.load("camera distance 8 angle 0.8 end\n"));
  await page.waitForFunction(() => document.querySelector("#lesson-verdict").textContent.startsWith("not yet"));
  assert.match(await page.$eval("#lesson-verdict", (element) => element.textContent), /distance 8 \(the goal: 10\)/);
  const pictures = await page.$eval("#lesson-pictures", (canvas) => [canvas.width, canvas.height]);
  assert.deepEqual(pictures, [2 * PAGE.width, PAGE.height]);
  await page.evaluate(() => window.rayrepl.load("camera distance 10 angle 0.8 end\n"));
  await page.waitForFunction(() => document.querySelector("#lesson-task").textContent.startsWith("step 2 of 3"));
  assert.match(await page.$eval("#lesson-verdict", (element) => element.textContent), /✓ step 1 done/);
  await page.close();
});

test("a pause in typing is one try of a lesson's step, however many inputs the scene holds", async () => {
  const page = await openPage();
  await page.selectOption("#lessons", "2");
  await page.waitForFunction(() => document.querySelector("#lesson-task").textContent.startsWith("step 1 of"));
  const setup = "camera distance 12 angle 0.8 end\n" +
    "put sphere center 0, 0, 0 radius 1 kd 0.8 ks 0.2 phong 20 color 255, 120, 40 end\n" +
    "put plane rotation 0, 0, 0 shift -1 kd 0.8 ks 0 phong 1 color 200, 200, 200 end\n" +
    "light vector 0, 0, -0.9 intensity 0.8 end\nambient 0.05\n";
  // Steps 1 and 2 done at once; step 3 asks for a weaker second light.
  await page.evaluate((text) => window.rayrepl.load(text), setup);
  await page.waitForFunction(() => document.querySelector("#lesson-task").textContent.startsWith("step 3 of"));
  const verdict = () => page.$eval("#lesson-verdict", (element) => element.textContent);
  // Two wrong tries bring the example: the first scene, of six inputs, is one.
  await page.evaluate((text) => window.rayrepl.load(text), `${setup}light vector 0, 0, 0.9 intensity 0.8 end\n`);
  await page.waitForFunction(() => document.querySelector("#lesson-verdict").textContent.startsWith("not yet"));
  assert.doesNotMatch(await verdict(), /for example/);
  assert.doesNotMatch(await verdict(), /:undo/, "the page has no :undo to offer");
  await page.evaluate((text) => window.rayrepl.load(text), `${setup}light vector 0, 0, 0.9 intensity 0.9 end\n`);
  await page.waitForFunction(() => document.querySelector("#lesson-verdict").textContent.includes("for example"));
  await page.close();
});

test("a scene that reads time has a slider and play; the downloads are the native files", async () => {
  const page = await openPage();
  assert.equal(await page.$eval("#time-controls", (element) => element.hidden), true, "hello.ray does not read time");
  const spiral = readFileSync(join(root, "scenarios/spiral.ray"), "utf8");
  const settings = { width: 96, height: 72, depth: 5, samples: 1, time: 3 };
  await checkScene(page, spiral, settings);
  assert.equal(await page.$eval("#time-controls", (element) => element.hidden), false);

  const [png] = await Promise.all([page.waitForEvent("download"), page.click("#download")]);
  const nativePng = runNative([sceneFile(spiral), ...settingsArgs(settings), "-q", "-o", "out.png"]);
  assert.equal(nativePng.status, 0, nativePng.stderr);
  assert.ok(readFileSync(await png.path()).equals(readFileSync(join(scratch, "out.png"))), "the PNG downloaded is the native file");

  await page.click("#play");
  await page.waitForFunction(() => document.querySelector("#status").textContent.startsWith("24 frames"), null, { timeout: 30_000 });
  const [apng] = await Promise.all([page.waitForEvent("download"), page.click("#download-animation")]);
  const nativeApng = runNative([sceneFile(spiral), "--width", 96, "--height", 72, "--anim", 24, "--fps", 12, "-q", "-o", "out.apng"]);
  assert.equal(nativeApng.status, 0, nativeApng.stderr);
  assert.ok(readFileSync(await apng.path()).equals(readFileSync(join(scratch, "out.apng"))), "the APNG downloaded is --anim's file");
  await page.click("#play");
  await page.close();
});

test("a scene too large for the browser's memory ends with a diagnostic, and the page goes on", async () => {
  const page = await openPage();
  const huge = "camera distance 8 angle 1 end\nambient 0.2\nproc f(d)\nif d < 26 then\n" +
    "put sphere center d, 0, 0 radius 0.1 kd 0.5 ks 0 phong 1 color 1, 2, 3 end\nf(d + 1)\nf(d + 1)\nend\nend\nf(0)\n";
  await page.evaluate((text) => window.rayrepl.load(text), huge);
  await page.waitForSelector("#diagnostics [data-line]", { timeout: 50_000 });
  const shown = await page.$eval("#diagnostics [data-line]", (element) => element.textContent);
  assert.match(shown, /^error: /);
  assert.equal(await page.$eval("#picture", (canvas) => canvas.dataset.state), "error");
  await checkScene(page, HELLO, SMALL);
  await page.close();
});

test("a setting past the command line's limit is refused with its message", async () => {
  const page = await openPage();
  await page.evaluate(() => window.rayrepl.settings({ width: 100000 }));
  await page.waitForFunction(() => document.querySelector("#picture").dataset.state === "error");
  const run = runNative([sceneFile(HELLO), "--width", "100000", "-o", "out.png"]);
  assert.equal(run.status, 2);
  const status = await page.$eval("#status", (element) => element.textContent);
  assert.ok(run.stderr.includes(`: ${status}\n`), `${status} is not in: ${run.stderr}`);
  await page.close();
});
