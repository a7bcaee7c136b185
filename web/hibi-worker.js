// A render worker of hibi.js (a module Web Worker, or a worker_threads Worker in Node), started
// by a model's renderAsync. It holds its own instance of hibi.wasm whose memory is a copy of
// the page's instance's memory: between calls the module's whole state (its statics, its
// allocator and every model) lies in that memory, so the copy holds the same models at the
// same handles. Each request draws one band of rows with the model's render_tile export and
// sends the band's layers back as transferred ArrayBuffers. Requests are answered in order.
//
// Messages in: { module } once, first; then { id, model, handle, slots, view, bits, tile,
// memory? }: `memory` (an ArrayBuffer or a SharedArrayBuffer) is copied over the instance's
// memory (an instance is made at the first copy, and again after a trap). Messages out: { id, layers } or { id, error, lost? } (`lost`: the
// instance trapped and is dropped; the next request brings memory again).

let module = null;
let exports = null;
let queue = Promise.resolve();
let post;

if (typeof self !== 'undefined' && typeof self.postMessage === 'function') {
  post = (message, transfer) => self.postMessage(message, transfer);
  self.onmessage = (e) => receive(e.data);
} else {
  const { parentPort } = await import('node:worker_threads');
  post = (message, transfer) => parentPort.postMessage(message, transfer);
  parentPort.on('message', receive);
}

function receive(message) {
  queue = queue.then(() => answer(message));
}

async function answer(m) {
  if (m.module) {
    module = m.module;
    return;
  }
  try {
    if (m.memory) {
      // The instance is reused: between calls its stack pointer is back at its start, as the
      // page's is, and memory beyond the copy is memory the copied allocator has not handed
      // out (it takes new memory from memory.grow's answer, wherever that lies).
      const instance = exports ? null : await WebAssembly.instantiate(module, {});
      const w = exports ?? instance.exports;
      exports = null;
      const pages = (m.memory.byteLength - w.memory.buffer.byteLength) / 65536;
      if (pages > 0) w.memory.grow(pages);
      new Uint8Array(w.memory.buffer).set(new Uint8Array(m.memory));
      exports = w;
    }
    if (!exports) throw new Error('render: the worker holds no copy of the memory');
    const w = exports;
    new Float64Array(w.memory.buffer, m.slots, m.view.length).set(m.view);
    const [x, y, width, height] = m.tile;
    if (w[`hibi_web_${m.model}_render_tile`](m.handle, m.slots, m.bits, x, y, width, height)) {
      const text = new Uint8Array(w.memory.buffer, w.hibi_web_text_ptr(), w.hibi_web_text_len());
      post({ id: m.id, error: new TextDecoder().decode(text) });
      return;
    }
    const layers = [];
    for (let i = 0; i < w.hibi_web_out_count(); i++) {
      const ptr = w.hibi_web_out_ptr(i);
      layers.push(w.memory.buffer.slice(ptr, ptr + w.hibi_web_out_bytes(i)));
    }
    w.hibi_web_out_clear();
    post({ id: m.id, layers }, layers);
  } catch (e) {
    // A trap leaves the instance's stack pointer where it was: the instance is not used again.
    exports = null;
    post({ id: m.id, error: `render: a worker failed: ${e && e.message ? e.message : e}`, lost: true });
  }
}
