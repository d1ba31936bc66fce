// The page's Worker (make web puts it after the library's WebAssembly module, whirlCore, in the
// page): it calls the flat interface of src/web/whirl_web.c and posts the JSON back. No physics
// here: a request is {id, kind, query}, the answer {id, kind, answer, ms, memory: the module's memory in bytes}.
"use strict";
const CALLS = { shape: "whirl_web_shape", branches: "whirl_web_branches", windows: "whirl_web_windows" };
let core = null;
const ready = whirlCore().then((m) => { core = m; postMessage({ type: "ready" }); },
                               (e) => postMessage({ type: "fatal", message: String(e) }));
onmessage = async (ev) => {
  await ready;
  const { id, kind, query } = ev.data;
  const t0 = performance.now();
  let answer;
  try {
    const ptr = core.ccall(CALLS[kind], "number", ["string"], [query]);
    if (!ptr) answer = { error: "out of memory", field: "" };
    else {
      answer = JSON.parse(core.UTF8ToString(ptr));
      core._whirl_web_free(ptr);
    }
  } catch (e) {
    answer = { error: "the engine failed: " + String(e), field: "" };
  }
  postMessage({ type: "answer", id, kind, answer, ms: performance.now() - t0,
                memory: core.HEAP8.buffer.byteLength });
};
