// The playground's numbers (docs/perf/front-ends.md, "The browser playground"): the
// render of scenarios/solar.ray at 640x480 in headless Chromium, by one
// worker and by the page's band workers, against the native binary on one
// thread, the time to the first picture, and
// the size of the WebAssembly module, gzipped.
//
//   node web/test/bench.mjs    (after web/build.sh and cargo build --release)

import { spawnSync } from "node:child_process";
import { readFileSync } from "node:fs";
import { join } from "node:path";
import { gzipSync } from "node:zlib";
import { launchBrowser, serve } from "./serve.mjs";

const root = join(import.meta.dirname, "../..");
const dist = join(root, "web/dist");
const RUNS = 7;
const median = (values) => [...values].sort((a, b) => a - b)[Math.floor(values.length / 2)];

const server = await serve(dist);
const browser = await launchBrowser();

const firsts = [];
for (let run = 0; run < RUNS; run++) {
  const page = await browser.newPage();
  const started = Date.now();
  await page.goto(`${server.base}`);
  await page.waitForFunction(() => document.querySelector("#picture").dataset.state === "done");
  firsts.push(Date.now() - started);
  await page.close();
}

/** The page's times for solar at 640x480 (its status line), opened at `query`. */
async function solarRenders(query) {
  const page = await browser.newPage();
  await page.goto(`${server.base}${query}`);
  await page.waitForFunction(() => document.querySelector("#picture").dataset.state === "done");
  const solar = readFileSync(join(root, "scenarios/solar.ray"), "utf8");
  const renders = [];
  for (let run = 0; run < RUNS; run++) {
    // A depth of 5 or 6 in turn, so that each is a new render of the same work.
    const depth = 5 + (run % 2);
    await page.evaluate(({ solar, depth }) => {
      window.rayrepl.settings({ width: 640, height: 480, depth, time: 0 });
      window.rayrepl.load(solar);
    }, { solar, depth });
    // The render starts after the typing pause, and takes longer than a frame: its start is seen.
    await page.waitForFunction(() => document.querySelector("#picture").dataset.state === "rendering");
    await page.waitForFunction(() => document.querySelector("#picture").dataset.state === "done");
    const status = await page.$eval("#status", (element) => element.textContent);
    renders.push(Number(/in (\d+) ms/.exec(status)[1]));
  }
  await page.close();
  return renders;
}

// One worker, then the page's own number of them (one a core, at most 8).
const oneWorker = await solarRenders("?workers=1");
const probe = await browser.newPage();
const workers = await probe.evaluate(() => Math.min(Math.max(navigator.hardwareConcurrency || 1, 1), 8));
await probe.close();
const manyWorkers = await solarRenders("");
await browser.close();
server.close();

const natives = [];
for (let run = 0; run < RUNS; run++) {
  const started = process.hrtime.bigint();
  const args = ["scenarios/solar.ray", "--width", "640", "--height", "480", "--threads", "1", "-q", "-o", "/tmp/rayrepl-bench-solar.png"];
  spawnSync(join(root, "target/release/rayrepl"), args, { cwd: root });
  natives.push(Number(process.hrtime.bigint() - started) / 1e6);
}

const wasm = readFileSync(join(dist, "rayrepl_web_bg.wasm"));
console.log(JSON.stringify({
  solar_640x480_page_one_worker_ms: { median: median(oneWorker), all: oneWorker },
  [`solar_640x480_page_${workers}_workers_ms`]: { median: median(manyWorkers), all: manyWorkers },
  solar_640x480_native_one_thread_ms: { median: Math.round(median(natives)), all: natives.map(Math.round) },
  first_picture_ms: { median: median(firsts), all: firsts },
  wasm_bytes: wasm.length,
  wasm_gzip_bytes: gzipSync(wasm, { level: 9 }).length,
}, null, 2));
