// mechkin view --live: the sliders' program (issue 30). Runs after app.js: loads the
// inlined WebAssembly core (MechkinLive, tools/build_live.sh), gives every number
// parameter a slider (its min/max, else ±20 %) and every driver one (scrubbing the run
// by the driver's value), and on a parameter's change recompiles the file with the
// overrides exactly as `mechkin run --set NAME=VALUE` does, re-solves the run (mechkin's
// Newton, the derivatives), writes the poses, times and series into MECHKIN_DATA in place
// and redraws (window.mechkin.refresh). A file that cannot close with the new values
// shows "cannot close: …" and keeps the last valid pose and run.
// Test hooks: window.mechkin.live (set, table, csv, run), the body's data-live-*
// attributes, and #live=NAME:VALUE,NAME:VALUE… (slider moves made after load, in order).
(function () {
  "use strict";
  const D = window.MECHKIN_DATA, LIVE = window.MECHKIN_LIVE, T = D.times, n = T.length;
  const body = document.body, bar = document.getElementById("bar");
  const box = document.createElement("span"), message = document.createElement("span"), mobility = document.createElement("span");
  box.id = "live";
  message.id = "live-message";
  message.style.color = "#f66";
  mobility.id = "live-mobility";
  bar.appendChild(box);
  bar.appendChild(mobility);
  bar.appendChild(message);
  let M = null, api = null, last = null;  // the module, its functions, the last valid table
  const moves = [];  // the #live= moves, made once the module is ready

  // A failure shown in the bar: `what` says which ("cannot close" for a move the file
  // cannot assemble or compile with; "live page" for the module itself).
  function fail(what, text) {
    message.textContent = what + ": " + text;
    body.setAttribute("data-live-state", "failed");
    body.setAttribute("data-live-message", message.textContent);
  }
  // The last table's columns: name → index.
  function columnIndex() {
    const cols = JSON.parse(M.UTF8ToString(api.columns())), at = new Map();
    cols.forEach(function (c, i) { at.set(c[0], i); });
    return { names: cols, at: at };
  }
  // The table into MECHKIN_DATA: times, the bodies' poses (x y z, e1 e2 e3 e0), the series.
  function apply(table) {
    const rows = table.rows, cols = table.cols, v = table.values, at = table.columns.at;
    const row = function (k) { return Math.min(k, rows - 1) * cols; };  // a stopped run: its last row held
    for (let k = 0; k < n; ++k) T[k] = v[row(k)];  // a stopped run: its last time held
    D.bodies.forEach(function (b) {
      const c = ["x", "y", "z", "e1", "e2", "e3", "e0"].map(function (s) { return at.get(b.name + "." + s); });
      for (let k = 0; k < n; ++k) for (let a = 0; a < 7; ++a) b.poses[7 * k + a] = v[row(k) + c[a]];
    });
    D.series.forEach(function (s) {
      const c = at.get(s.name);
      if (c !== undefined) for (let k = 0; k < n; ++k) s.values[k] = k < rows ? v[row(k) + c] : null;
    });
    window.mechkin.refresh();
  }
  // Re-solves with the overrides set: true, or false with the message shown (nothing changed).
  function resolve() {
    const t0 = performance.now();
    const ptr = api.run(LIVE.steps, LIVE.order);
    const solved = performance.now();
    if (!ptr) { fail("cannot close", M.UTF8ToString(api.error())); return false; }
    const rows = api.rows(), cols = api.cols();
    last = { rows: rows, cols: cols, values: new Float64Array(M.HEAPF64.buffer, ptr, rows * cols).slice(), columns: columnIndex() };
    const status = JSON.parse(M.UTF8ToString(api.status()));
    // The plots' marks are this run's (a singular position, limit, stop, ...), drawn by apply's refresh.
    D.marks.length = 0;
    status.marks.forEach(function (m) { D.marks.push(m); });
    apply(last);
    message.textContent = status.complete ? status.notes.map(function (s) { return s.split("\n")[0]; }).join("; ")
                                          : "run stopped: " + status.message.split("\n")[0];
    body.setAttribute("data-live-marks", status.marks.map(function (m) { return m.kind + "@" + m.t; }).join(","));
    showMobility();
    body.setAttribute("data-live-state", status.complete ? "ok" : "partial");
    body.setAttribute("data-live-message", message.textContent);
    body.setAttribute("data-live-solve-ms", (solved - t0).toFixed(2));
    body.setAttribute("data-live-redraw-ms", (performance.now() - solved).toFixed(2));
    body.setAttribute("data-live-rows", String(rows));
    return true;
  }
  function showMobility() {
    const r = JSON.parse(M.UTF8ToString(api.mobility()));
    mobility.textContent = r.assembled === undefined ? "" : "mobility " + r.mobility + (r.redundant ? " (" + r.redundant + " redundant)" : "") +
      ", driving " + r.driving + (r.singular_lost ? ", singular position at the design pose" : "");
    body.setAttribute("data-live-mobility", String(r.mobility));
  }
  function slider(label, min, max, value, onInput) {
    const wrap = document.createElement("label"), input = document.createElement("input"), shown = document.createElement("span");
    input.type = "range";
    input.min = String(min);
    input.max = String(max);
    input.step = String((max - min) / 1000);
    input.value = String(value);
    shown.textContent = " " + Number(Number(value).toPrecision(6));
    wrap.appendChild(document.createTextNode(" " + label + " "));
    wrap.appendChild(input);
    wrap.appendChild(shown);
    input.style.width = "110px";
    input.addEventListener("input", function () { showValue(input); onInput(Number(input.value)); });
    box.appendChild(wrap);
    return input;
  }
  // The number beside a slider (the span after it) shows the slider's value.
  function showValue(input) { input.nextSibling.textContent = " " + Number(Number(input.value).toPrecision(6)); }
  const inputs = new Map();
  function parameterSliders() {
    LIVE.parameters.forEach(function (p) {
      if (p.set) api.set(p.name, p.value);  // the page's --set values
      inputs.set(p.name, slider(p.name, p.min, p.max, p.value, function (value) { setParameter(p.name, value); }));
    });
  }
  // A parameter's new value: the override set, the run re-solved; on a failure the
  // last valid value comes back, to the override and to the slider (which shows the
  // value in use), so the next move starts from a valid file.
  const good = new Map(LIVE.parameters.map(function (p) { return [p.name, p.value]; }));
  function setParameter(name, value) {
    api.set(name, value);
    body.setAttribute("data-live-set", name + "=" + String(value));
    if (resolve()) { good.set(name, value); return true; }
    api.set(name, good.get(name));
    const input = inputs.get(name);
    if (input) { input.value = String(good.get(name)); showValue(input); }
    body.setAttribute("data-live-kept", name + "=" + input.value);
    return false;
  }
  // A driver's slider scrubs the run: the first time its value reaches the slider's.
  function driverSliders() {
    LIVE.drivers.forEach(function (d) {
      const v = d.values, lo = Math.min.apply(null, v), hi = Math.max.apply(null, v);
      if (!(hi > lo)) return;
      slider(d.name + " [" + d.unit + "]", lo, hi, v[0], function (value) {
        for (let k = 0; k + 1 < v.length; ++k) {
          const a = v[k], b = v[k + 1];
          if ((value - a) * (value - b) <= 0 && k + 1 < n) {
            const u = b === a ? 0 : (value - a) / (b - a);
            window.mechkin.setTime(T[k] + u * (T[k + 1] - T[k]));
            return;
          }
        }
      });
    });
  }
  // A move by script exactly as a hand makes it: the input's value, then its input event.
  function move(name, value) {
    const input = inputs.get(name);
    if (!input) { (window.MECHKIN_ERRORS || []).push("#live: no parameter slider '" + name + "'"); return; }
    input.value = String(value);
    input.dispatchEvent(new Event("input"));
  }
  function csv() {
    if (!last) return "";
    const lines = [last.columns.names.map(function (c) { return c[1]; }).join(",")];
    for (let k = 0; k < last.rows; ++k) lines.push(Array.from(last.values.subarray(k * last.cols, (k + 1) * last.cols)).join(","));
    return lines.join("\n") + "\n";
  }
  window.mechkin.live = {
    set: function (name, value) { move(name, value); return body.getAttribute("data-live-state"); },
    table: function () { return last; },
    csv: csv,
    // The re-solve alone, `repeats` times (tools/live_benchmark.py): the milliseconds of each.
    time: function (steps, repeats) {
      const out = [];
      for (let r = 0; r < repeats; ++r) { const t0 = performance.now(); api.run(steps, LIVE.order); out.push(performance.now() - t0); }
      return out;
    },
  };
  new URLSearchParams(location.hash.slice(1)).getAll("live").forEach(function (list) {
    list.split(",").forEach(function (m) { const at = m.lastIndexOf(":"); moves.push([m.slice(0, at), Number(m.slice(at + 1))]); });
  });
  body.setAttribute("data-live-state", "loading");
  MechkinLive().then(function (module) {
    M = module;
    api = {
      load: M.cwrap("mk_live_load", "number", ["string"]), set: M.cwrap("mk_live_set", null, ["string", "number"]),
      run: M.cwrap("mk_live_run", "number", ["number", "number"]), rows: M._mk_live_rows, cols: M._mk_live_cols,
      columns: M._mk_live_columns, status: M._mk_live_status, error: M._mk_live_error, mobility: M._mk_live_mobility,
    };
    if (api.load(LIVE.spec)) { fail("live page", M.UTF8ToString(api.error())); return; }
    parameterSliders();
    driverSliders();
    resolve();
    // Each scripted move's outcome, for the tests: state and the first trace's points.
    moves.forEach(function (m, i) {
      move(m[0], m[1]);
      body.setAttribute("data-live-move-" + i, body.getAttribute("data-live-state") + ";" + traceText());
    });
    if (moves.length) document.getElementById("export").textContent = csv();
    bench();
    body.setAttribute("data-live-ready", "1");
  }, function (e) { fail("live page", "the WebAssembly module did not start: " + e); });
  // #bench=K (tools/live_benchmark.py): K re-solves as a slider makes them — the first
  // parameter alternately 1 % above and at its value, each recompiled, solved and
  // redrawn. The benchmark times the page in wall-clock time against K = 0 (headless
  // Chromium's virtual time stops performance.now()).
  function bench() {
    const k = Number(new URLSearchParams(location.hash.slice(1)).get("bench") || 0), p = LIVE.parameters[0];
    for (let i = 0; p && i < k; ++i) setParameter(p.name, i % 2 ? p.value : p.value * 1.01);
    if (k) body.setAttribute("data-live-bench", String(k));
  }
  // The first trace (coupler curve) as drawn: its body point at every frame.
  function traceText() {
    const tr = D.traces[0];
    if (!tr) return "";
    const out = [];
    for (let k = 0; k < n; ++k) out.push(window.mechkin.project ? pointAt(tr, k).map(function (x) { return x.toPrecision(12); }).join(" ") : "");
    return out.join("|");
  }
  function pointAt(tr, k) {
    const a = D.bodies[tr.body].poses, o = 7 * k, p = tr.point;
    const q = new THREE.Quaternion(a[o + 3], a[o + 4], a[o + 5], a[o + 6]), v = new THREE.Vector3(p[0], p[1], p[2]).applyQuaternion(q);
    return [v.x + a[o], v.y + a[o + 1], v.z + a[o + 2]];
  }
})();
