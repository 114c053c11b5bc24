// Bundles the page into dist/ (called by build.sh, after the WebAssembly
// module and its JavaScript glue are made in PKG): main.js and worker.js
// with CodeMirror, by esbuild; the bundled scenarios and the lessons'
// titles as the module `rayrepl-examples`; index.html and page.css as they are.

import { build } from "esbuild";
import { copyFileSync, mkdirSync, readdirSync, readFileSync } from "node:fs";
import { join, resolve } from "node:path";

const [pkg, dist] = process.argv.slice(2).map((path) => resolve(path));
const root = join(import.meta.dirname, "..");
const source = join(import.meta.dirname, "src");

/** The scenarios (name and text) and the lessons (number and title), read from the repository. */
function examples() {
  const scenarios = readdirSync(join(root, "scenarios"))
    .filter((file) => file.endsWith(".ray"))
    .sort()
    .map((file) => ({ name: file.slice(0, -".ray".length), text: readFileSync(join(root, "scenarios", file), "utf8") }));
  const lessons = readdirSync(join(root, "lessons"))
    .filter((file) => /^\d+-.*\.md$/.test(file))
    .map((file) => ({
      number: Number.parseInt(file, 10),
      title: readFileSync(join(root, "lessons", file), "utf8").split("\n")[0].replace(/^#\s*/, ""),
    }))
    .sort((a, b) => a.number - b.number);
  return { scenarios, lessons };
}

const repository = {
  name: "repository",
  setup(builder) {
    builder.onResolve({ filter: /^rayrepl-examples$/ }, () => ({ path: "examples", namespace: "repository" }));
    builder.onLoad({ filter: /.*/, namespace: "repository" }, () => ({
      contents: JSON.stringify(examples()),
      loader: "json",
    }));
  },
};

mkdirSync(dist, { recursive: true });
await build({
  entryPoints: [join(source, "main.js"), join(source, "worker.js")],
  outdir: dist,
  bundle: true,
  format: "esm",
  minify: true,
  target: "es2022",
  alias: { "rayrepl-web": join(pkg, "rayrepl_web.js") },
  plugins: [repository],
  logLevel: "warning",
});
for (const file of ["index.html", "page.css"]) copyFileSync(join(source, file), join(dist, file));
