// A Reply of the WebAssembly module (web/src/lib.rs) as plain data: its
// outputs parsed, each picture as RGBA bytes for a canvas and as the PNG
// file the command line writes, an animation as its APNG file. The worker and the Node test read replies
// this way.

/** `reply` as `{ end, outputs, images, animation, band }` (the APNG file
 * of the frames `:play` showed, or `null`; the RGBA bytes of the rows
 * `render_rows` rendered, or `null`), the Reply freed. */
export function replyOf(reply) {
  try {
    const outputs = JSON.parse(reply.outputs);
    const images = [];
    const keep = (image) => {
      images[image.index] = { width: image.width, height: image.height, rgba: reply.rgba(image.index), png: reply.png(image.index) };
    };
    for (const output of outputs) {
      if (output.image) keep(output.image);
      for (const frame of output.frames ?? []) keep(frame);
    }
    const animation = outputs.some((output) => output.kind === "frames") ? reply.apng() : null;
    const band = reply.band();
    return { end: reply.end, outputs, images, animation, band: band.length ? band : null };
  } finally {
    reply.free();
  }
}
