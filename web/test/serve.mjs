// What the browser test and the benchmark share: web/dist/ served on
// 127.0.0.1 at a free port (the files as they are, with the types a
// browser wants: a module worker must be JavaScript; 404 for anything
// else), and Debian's Chromium started headless by playwright-core.

import { createReadStream, existsSync, statSync } from "node:fs";
import { createServer } from "node:http";
import { extname, join, normalize } from "node:path";
import { chromium } from "playwright-core";

const TYPES = { ".html": "text/html", ".js": "text/javascript", ".css": "text/css", ".wasm": "application/wasm" };

/** Serves `dist`; resolves to `{ base, close }`, `base` the page's address. */
export async function serve(dist) {
  const server = createServer((request, response) => {
    const path = normalize(decodeURIComponent(new URL(request.url, "http://localhost").pathname));
    const file = join(dist, path.endsWith("/") ? `${path}index.html` : path);
    if (!file.startsWith(dist) || !existsSync(file) || !statSync(file).isFile()) {
      response.writeHead(404).end();
      return;
    }
    response.writeHead(200, { "content-type": TYPES[extname(file)] ?? "application/octet-stream" });
    createReadStream(file).pipe(response);
  });
  await new Promise((resolve) => server.listen(0, "127.0.0.1", resolve));
  return { base: `http://127.0.0.1:${server.address().port}/`, close: () => server.close() };
}

/** Chromium at RAYREPL_CHROMIUM (Debian's /usr/bin/chromium), headless; never a browser playwright downloads. */
export function launchBrowser() {
  return chromium.launch({
    executablePath: process.env.RAYREPL_CHROMIUM ?? "/usr/bin/chromium",
    // As root its sandbox cannot start; a container's /dev/shm may be too small for its pages.
    args: ["--no-sandbox", "--disable-dev-shm-usage"],
  });
}
