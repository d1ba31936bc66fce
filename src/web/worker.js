// The page's Worker (make web puts it after the library's WebAssembly module, whirlCore, in the
// page): it calls the flat interface of src/web/whirl_web.c and posts the JSON back. No physics
// here: a request is {id, kind, query}, the answer {id, kind, answer, ms, memory: the module's
// memory in bytes}. A run (kind "run") is computed RUN_CHUNK frames at a time, each chunk posted
// as {type: "frames", id, answer} as soon as it is computed, and the next chunk left for after
// the messages waiting (so that a shape asked for meanwhile is answered between two chunks);
// a new run ends the one in progress (its id gets no more messages).
"use strict";
const CALLS = { shape: "whirl_web_shape", branches: "whirl_web_branches", windows: "whirl_web_windows" };
const RUN_CHUNK = 10;
let core = null, run = null; // run: {id, ptr} of the run in progress
const ready = whirlCore().then((m) => { core = m; postMessage({ type: "ready" }); },
                               (e) => postMessage({ type: "fatal", message: String(e) }));
function call(fn, args) {
  let answer;
  try {
    const ptr = fn(...args);
    if (!ptr) answer = { error: "out of memory", field: "" };
    else {
      answer = JSON.parse(core.UTF8ToString(ptr));
      core._whirl_web_free(ptr);
    }
  } catch (e) {
    answer = { error: "the engine failed: " + String(e), field: "" };
  }
  return answer;
}
function endRun() {
  if (run) core._whirl_web_run_free(run.ptr);
  run = null;
}
function runChunk(id) {
  if (!run || run.id !== id) return; // stopped, or replaced by a newer run
  const t0 = performance.now();
  const answer = call(core._whirl_web_run_next, [run.ptr, RUN_CHUNK]);
  const last = !!(answer.error || answer.done);
  if (last) endRun();
  postMessage({ type: last ? "answer" : "frames", id, kind: "run", answer,
                ms: performance.now() - t0, memory: core.HEAP8.buffer.byteLength });
  if (!last) setTimeout(() => runChunk(id), 0);
}
onmessage = async (ev) => {
  await ready;
  const { id, kind, query } = ev.data;
  if (kind === "run") {
    endRun();
    const ptr = core.ccall("whirl_web_run_alloc", "number", ["string"], [query]);
    if (!ptr) postMessage({ type: "answer", id, kind, answer: { error: "out of memory", field: "" } });
    else { run = { id, ptr }; runChunk(id); }
    return;
  }
  const t0 = performance.now();
  const answer = call((q) => core.ccall(CALLS[kind], "number", ["string"], [q]), [query]);
  postMessage({ type: "answer", id, kind, answer, ms: performance.now() - t0,
                memory: core.HEAP8.buffer.byteLength });
};
