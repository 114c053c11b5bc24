// Share links: the scene and its settings in the URL's fragment (never
// sent to a server), the scene compressed with deflate-raw and written in
// base64url: `#v=1&w=640&h=480&d=5&s=1&t=0&scene=...`.

/** The longest link the page makes or opens, in characters: far below
 * what browsers and chat programs take (Chromium takes 2 MB), far above
 * any lesson's scene. */
export const MOST_LINK_CHARACTERS = 32000;
/** The longest scene a link may unpack to, in bytes (a scene file of the
 * command line is at most this too, in practice). */
export const MOST_SCENE_BYTES = 1 << 20;

const SETTINGS = [
  ["w", "width"],
  ["h", "height"],
  ["d", "depth"],
  ["s", "samples"],
  ["t", "time"],
];

/** Bytes through a CompressionStream or DecompressionStream, at most `limit` of them out. */
async function through(stream, bytes, limit) {
  const writer = stream.writable.getWriter();
  writer.write(bytes).catch(() => {});
  writer.close().catch(() => {});
  const chunks = [];
  let length = 0;
  const reader = stream.readable.getReader();
  for (;;) {
    const { done, value } = await reader.read();
    if (done) break;
    length += value.length;
    if (length > limit) {
      reader.cancel().catch(() => {});
      throw new Error(`it unpacks to more than ${limit} bytes`);
    }
    chunks.push(value);
  }
  const out = new Uint8Array(length);
  let at = 0;
  for (const chunk of chunks) {
    out.set(chunk, at);
    at += chunk.length;
  }
  return out;
}

function toBase64url(bytes) {
  let binary = "";
  for (const byte of bytes) binary += String.fromCharCode(byte);
  return btoa(binary).replaceAll("+", "-").replaceAll("/", "_").replace(/=+$/, "");
}

function fromBase64url(text) {
  if (!/^[A-Za-z0-9_-]*$/.test(text)) throw new Error("its scene holds characters base64url does not use");
  const binary = atob(text.replaceAll("-", "+").replaceAll("_", "/"));
  return Uint8Array.from(binary, (c) => c.charCodeAt(0));
}

/** The fragment (`#...`) of a link to `scene` with `settings`; fails, saying so, when it would be too long. */
export async function fragmentOf(scene, settings) {
  const packed = await through(new CompressionStream("deflate-raw"), new TextEncoder().encode(scene), Infinity);
  const parts = ["v=1", ...SETTINGS.map(([key, name]) => `${key}=${settings[name]}`), `scene=${toBase64url(packed)}`];
  const fragment = `#${parts.join("&")}`;
  if (fragment.length > MOST_LINK_CHARACTERS) {
    throw new Error(
      `the scene is too long to share by link: its link would have ${fragment.length} characters, and links have at most ${MOST_LINK_CHARACTERS}`,
    );
  }
  return fragment;
}

/** The scene and settings a link's fragment holds, `null` for a fragment
 * that is no share link; fails with what is wrong with a damaged or too long one. */
export async function readFragment(fragment) {
  if (!fragment.startsWith("#") || !fragment.includes("scene=")) return null;
  if (fragment.length > MOST_LINK_CHARACTERS) {
    throw new Error(`this link is too long: ${fragment.length} characters, and links have at most ${MOST_LINK_CHARACTERS}`);
  }
  const fields = new URLSearchParams(fragment.slice(1));
  if (fields.get("v") !== "1") throw new Error("this link was made by another version of the page (no `v=1`)");
  const settings = {};
  for (const [key, name] of SETTINGS) {
    const value = Number(fields.get(key));
    if (!fields.has(key) || !Number.isFinite(value)) throw new Error(`this link is damaged: its ${name} is not a number`);
    settings[name] = value;
  }
  let bytes;
  try {
    bytes = await through(new DecompressionStream("deflate-raw"), fromBase64url(fields.get("scene")), MOST_SCENE_BYTES);
  } catch (error) {
    throw new Error(`this link is damaged: its scene cannot be unpacked (${error.message})`);
  }
  let scene;
  try {
    scene = new TextDecoder("utf-8", { fatal: true }).decode(bytes);
  } catch {
    throw new Error("this link is damaged: its scene is not UTF-8 text");
  }
  return { scene, settings };
}
