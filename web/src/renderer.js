// A worker running the session core (worker.js), one request at a time.
// WebAssembly runs a request to its end without looking at messages, so a
// request is abandoned by ending the worker: a new one starts at once from
// the module compiled when the page opened. A request that runs past
// MOST_REQUEST_MS, or that the stop button stops, ends the same way; a
// worker that traps (a runaway recursion past the stack, memory that
// cannot grow) is replaced too, and its request answered with why.

/** How long a request may run before its worker is ended. */
export const MOST_REQUEST_MS = 60_000;

export class Renderer {
  /**
   * A worker of `workerUrl` given `module` (a promise of the compiled
   * WebAssembly module). With `supersede`, a request ends the one
   * running; without, it waits for it (only the newest waiting one is kept).
   */
  constructor(module, workerUrl, { supersede }) {
    this.module = module;
    this.workerUrl = workerUrl;
    this.supersede = supersede;
    this.running = null;
    this.waiting = null;
    this.nextId = 1;
    this.ready = this.start();
  }

  /** Starts a worker and waits until it has instantiated the module. */
  async start() {
    const module = await this.module;
    const worker = new Worker(this.workerUrl, { type: "module" });
    this.worker = worker;
    worker.onmessage = ({ data }) => this.answered(worker, data);
    worker.onerror = (event) => {
      event.preventDefault();
      this.failed(worker, `the renderer failed (${event.message || "it trapped"}): it was started again`);
    };
    await new Promise((resolve) => {
      this.started = resolve;
      worker.postMessage({ kind: "init", module });
    });
  }

  /** Runs `message` in the worker; the reply, or `{ superseded }` or `{ stopped }` when it gave none. */
  request(message) {
    return new Promise((resolve) => {
      const request = { message: { ...message, id: this.nextId++ }, resolve };
      if (!this.running) return this.send(request);
      if (this.supersede) {
        this.end({ superseded: true });
        return this.send(request);
      }
      this.waiting?.resolve({ superseded: true });
      this.waiting = request;
    });
  }

  /** Ends the request running (and the one waiting), answering `{ stopped: reason }`. */
  stop(reason) {
    this.waiting?.resolve({ stopped: reason, end: "stopped", outputs: [], images: [] });
    this.waiting = null;
    if (this.running) this.end({ stopped: reason, end: "stopped", outputs: [], images: [] });
  }

  async send(request) {
    this.running = request;
    await this.ready;
    if (this.running !== request) return;
    request.timer = setTimeout(
      () => this.end({ stopped: `stopped after ${MOST_REQUEST_MS / 1000} s`, end: "stopped", outputs: [], images: [] }),
      MOST_REQUEST_MS,
    );
    this.worker.postMessage(request.message);
  }

  /** Ends the worker and its request, answered with `reply`, and starts another. */
  end(reply) {
    const request = this.running;
    this.running = null;
    clearTimeout(request.timer);
    this.worker.terminate();
    this.ready = this.start();
    request.resolve(reply);
    this.next();
  }

  answered(worker, data) {
    if (worker !== this.worker) return;
    if (data.kind === "ready") return this.started();
    const request = this.running;
    if (!request || request.message.id !== data.id) return;
    clearTimeout(request.timer);
    this.running = null;
    request.resolve(data);
    this.next();
  }

  failed(worker, reason) {
    if (worker !== this.worker || !this.running) return;
    this.end({ stopped: reason, end: "stopped", outputs: [], images: [] });
  }

  next() {
    const waiting = this.waiting;
    this.waiting = null;
    if (waiting) this.send(waiting);
  }
}
