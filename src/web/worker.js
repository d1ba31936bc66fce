// The page's Worker (make web puts it after the library's WebAssembly module, whirlCore, in the
// page): it calls the flat interface of src/web/whirl_web.c and posts the JSON back. No physics
// here: a request is {id, kind, query}, the answer {id, kind, answer, ms, memory: the module's
// memory in bytes}. A run (kind "run") is computed RUN_CHUNK frames at a time (more for fewer than
// 30 links), each chunk posted
// as {type: "frames", id, answer} as soon as it is computed, and the next chunk left for after
// the messages waiting (so that a shape asked for meanwhile is answered between two chunks);
// a new run ends the one in progress (its id gets no more messages). A shaken run (kind "shake",
// whirl_web_shake_alloc) is read the same way. The Floquet multipliers (kind "floquet",
// whirl_web_floquet: one call of up to tens of seconds) are asked of a second Worker of this
// script, which the page ends to stop them without stopping the first.
"use strict";
const CALLS = { shape: "whirl_web_shape", branches: "whirl_web_branches", windows: "whirl_web_windows",
                floquet: "whirl_web_floquet" };
const RUNS = { run: "whirl_web_run_alloc", shake: "whirl_web_shake_alloc" };
const RUN_CHUNK = 10, RUN_CHUNK_VALUES = 300;
let core = null, run = null; // run: {id, ptr, kind} of the run in progress
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
  const answer = call(core._whirl_web_run_next, [run.ptr, run.chunk]), kind = run.kind;
  // a short chain's frames are cheap: more of them to a chunk (about RUN_CHUNK_VALUES values)
  if (answer.links) run.chunk = Math.max(RUN_CHUNK, Math.floor(RUN_CHUNK_VALUES / answer.links));
  const last = !!(answer.error || answer.done);
  if (last) endRun();
  postMessage({ type: last ? "answer" : "frames", id, kind, answer,
                ms: performance.now() - t0, memory: core.HEAP8.buffer.byteLength });
  if (!last) setTimeout(() => runChunk(id), 0);
}
onmessage = async (ev) => {
  await ready;
  const { id, kind, query } = ev.data;
  if (RUNS[kind]) {
    endRun();
    const ptr = core.ccall(RUNS[kind], "number", ["string"], [query]);
    if (!ptr) postMessage({ type: "answer", id, kind, answer: { error: "out of memory", field: "" } });
    else { run = { id, ptr, kind, chunk: RUN_CHUNK }; runChunk(id); }
    return;
  }
  const t0 = performance.now();
  const answer = call((q) => core.ccall(CALLS[kind], "number", ["string"], [q]), [query]);
  postMessage({ type: "answer", id, kind, answer, ms: performance.now() - t0,
                memory: core.HEAP8.buffer.byteLength });
};
