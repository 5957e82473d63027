// mechkin view: the page's program. Reads window.MECHKIN_DATA (written by
// src/io/viewer.cpp), draws each body as a stick figure of its joint and output
// points with joint glyphs by type, animates the table's poses (interpolated in
// time), traces output points, and plots any column against time (SVG) with a
// cursor that follows the animation. Test hooks: window.mechkin.
(function () {
  "use strict";
  const D = window.MECHKIN_DATA;
  const status = document.getElementById("status");
  const errors = window.MECHKIN_ERRORS || [];
  function flushErrors() { if (errors.length) document.body.setAttribute("data-errors", errors.join(" | ")); }

  const view = document.getElementById("view");
  const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(1);
  renderer.setClearColor(0xf4f4f4);
  view.appendChild(renderer.domElement);
  const scene = new THREE.Scene();
  const L = D.size > 0 ? D.size : 1;
  const camera = new THREE.PerspectiveCamera(40, 1, L * 1e-3, L * 1e3);
  const controls = new THREE.OrbitControls(camera, renderer.domElement);
  scene.add(new THREE.HemisphereLight(0xffffff, 0x808080, 0.9));
  const sun = new THREE.DirectionalLight(0xffffff, 0.6);
  sun.position.set(1, 2, 3);
  scene.add(sun);

  const palette = [0x1f77b4, 0xd62728, 0x2ca02c, 0xff7f0e, 0x9467bd, 0x8c564b, 0xe377c2, 0x17becf, 0xbcbd22, 0x7f7f7f];
  const thick = L * 0.02;
  function material(color) { return new THREE.MeshLambertMaterial({ color: color }); }
  function v3(a) { return new THREE.Vector3(a[0], a[1], a[2]); }
  function stick(a, b, r, mat) {
    const d = new THREE.Vector3().subVectors(b, a), len = d.length();
    const m = new THREE.Mesh(new THREE.CylinderBufferGeometry(r, r, Math.max(len, 1e-9), 12), mat);
    m.position.copy(a).add(b).multiplyScalar(0.5);
    if (len > 0) m.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), d.normalize());
    return m;
  }
  function ball(p, r, mat) { const m = new THREE.Mesh(new THREE.SphereBufferGeometry(r, 16, 12), mat); m.position.copy(p); return m; }

  // Bodies: sticks from the centroid of their points (a bar between two points).
  const groups = [], pickable = [];
  D.bodies.forEach(function (b, i) {
    const g = new THREE.Group(), mat = material(palette[i % palette.length]);
    const pts = b.points.map(v3);
    if (pts.length === 2) g.add(stick(pts[0], pts[1], thick, mat));
    else if (pts.length > 2) {
      const c = new THREE.Vector3();
      pts.forEach(function (p) { c.add(p); });
      c.multiplyScalar(1 / pts.length);
      pts.forEach(function (p) { g.add(stick(c, p, thick, mat)); });
      g.add(ball(c, thick * 1.3, mat));
    } else if (pts.length === 1) g.add(ball(pts[0], thick * 2, mat));
    if (b.shape) {  // the user's own geometry, semi-transparent over the sticks
      const sm = new THREE.MeshLambertMaterial({ color: palette[i % palette.length], transparent: true, opacity: 0.45 });
      let geo;
      if (b.shape.type === "box") geo = new THREE.BoxBufferGeometry(b.shape.size[0], b.shape.size[1], b.shape.size[2]);
      else if (b.shape.type === "cylinder") geo = new THREE.CylinderBufferGeometry(b.shape.radius, b.shape.radius, b.shape.length, 24);
      else geo = new THREE.SphereBufferGeometry(b.shape.radius, 24, 16);
      const mesh = new THREE.Mesh(geo, sm);
      mesh.position.copy(v3(b.shape.center));
      if (b.shape.type === "cylinder") mesh.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), v3(b.shape.axis).normalize());
      g.add(mesh);
    }
    g.traverse(function (o) { if (o.isMesh) { o.userData.label = b.name; pickable.push(o); } });
    g.userData.color = palette[i % palette.length];
    scene.add(g);
    groups.push(g);
  });
  const ground = new THREE.Group();
  scene.add(ground);
  function parent(body) { return body < 0 ? ground : groups[body]; }

  // Joint glyphs by type, fixed in body1 (ground parts grey).
  const jointMat = material(0x444444), groundMat = material(0x999999);
  D.joints.forEach(function (j) {
    const o = v3(j.origin), h = v3(j.axis).normalize(), s = thick;
    const mat = j.body1 < 0 ? groundMat : jointMat;
    let glyph;
    if (j.type === "revolute" || j.type === "screw") glyph = stick(o.clone().addScaledVector(h, -3 * s), o.clone().addScaledVector(h, 3 * s), 1.8 * s, mat);
    else if (j.type === "cylindrical") glyph = stick(o.clone().addScaledVector(h, -5 * s), o.clone().addScaledVector(h, 5 * s), 1.4 * s, mat);
    else if (j.type === "prismatic") {
      glyph = new THREE.Mesh(new THREE.BoxBufferGeometry(3 * s, 8 * s, 3 * s), mat);
      glyph.position.copy(o);
      glyph.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), h);
    } else if (j.type === "spherical") glyph = ball(o, 2.2 * s, mat);
    else if (j.type === "universal") {
      glyph = new THREE.Group();
      const h2 = v3(j.axis2).normalize();
      glyph.add(stick(o.clone().addScaledVector(h, -3 * s), o.clone().addScaledVector(h, 3 * s), s, mat));
      glyph.add(stick(o.clone().addScaledVector(h2, -3 * s), o.clone().addScaledVector(h2, 3 * s), s, mat));
    } else if (j.type === "planar") {
      glyph = new THREE.Mesh(new THREE.BoxBufferGeometry(8 * s, 0.6 * s, 8 * s), mat);
      glyph.position.copy(o);
      glyph.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), h);
    }
    if (glyph) { glyph.traverse(function (x) { if (x.isMesh) { x.userData.label = j.name + " (" + j.type + ")"; pickable.push(x); } }); parent(j.body1).add(glyph); }
  });
  // Distance links: a thin line between their two body points, updated per frame.
  const links = D.joints.filter(function (j) { return j.type === "distance"; }).map(function (j) {
    const geo = new THREE.BufferGeometry();
    geo.setAttribute("position", new THREE.Float32BufferAttribute([0, 0, 0, 0, 0, 0], 3));
    const line = new THREE.Line(geo, new THREE.LineBasicMaterial({ color: 0x333333 }));
    scene.add(line);
    return { j: j, line: line };
  });
  scene.add(new THREE.AxesHelper(L * 0.3));
  const grid = new THREE.GridHelper(L * 4, 20, 0xbbbbbb, 0xdddddd);
  grid.position.y = D.floor;
  scene.add(grid);

  // Poses: frame k of body i at D.bodies[i].poses[7k .. 7k+6] = x y z qx qy qz qw.
  const T = D.times, n = T.length;
  function pose(i, k, pos, q) {
    const a = D.bodies[i].poses, o = 7 * k;
    pos.set(a[o], a[o + 1], a[o + 2]);
    q.set(a[o + 3], a[o + 4], a[o + 5], a[o + 6]);
  }
  const p0 = new THREE.Vector3(), p1 = new THREE.Vector3(), q0 = new THREE.Quaternion(), q1 = new THREE.Quaternion();
  function frameAt(t) {
    if (t <= T[0]) return [0, 0];
    if (t >= T[n - 1]) return [n - 1, 0];
    let lo = 0, hi = n - 1;
    while (hi - lo > 1) { const mid = (lo + hi) >> 1; if (T[mid] <= t) lo = mid; else hi = mid; }
    return [lo, (t - T[lo]) / (T[lo + 1] - T[lo])];
  }
  function globalPoint(body, local, out) {
    const g = parent(body);
    return out.copy(v3(local)).applyQuaternion(g.quaternion).add(g.position);
  }
  let current = T[0];
  function setTime(t) {
    current = Math.min(Math.max(t, T[0]), T[n - 1]);
    const fk = frameAt(current), k = fk[0], u = fk[1];
    groups.forEach(function (g, i) {
      pose(i, k, p0, q0);
      if (u > 0 && k + 1 < n) { pose(i, k + 1, p1, q1); p0.lerp(p1, u); THREE.Quaternion.slerp(q0, q1, q0, u); }
      g.position.copy(p0);
      g.quaternion.copy(q0);
    });
    links.forEach(function (l) {
      const a = globalPoint(l.j.body1, l.j.origin, new THREE.Vector3()), b = globalPoint(l.j.body2, l.j.origin2, new THREE.Vector3());
      l.line.geometry.attributes.position.setXYZ(0, a.x, a.y, a.z);
      l.line.geometry.attributes.position.setXYZ(1, b.x, b.y, b.z);
      l.line.geometry.attributes.position.needsUpdate = true;
    });
    slider.value = String(Math.round(1000 * (current - T[0]) / Math.max(T[n - 1] - T[0], 1e-300)));
    clock.textContent = "t = " + current.toPrecision(6) + " s";
    plots.cursor(current);
  }

  // Traces of output points over the whole motion (coupler curves).
  const traces = new THREE.Group();
  D.traces.forEach(function (tr) {
    const pts = [], pos = new THREE.Vector3(), q = new THREE.Quaternion(), bi = tr.body;
    for (let k = 0; k < n; ++k) {
      if (bi >= 0) { pose(bi, k, pos, q); pts.push(v3(tr.point).applyQuaternion(q).add(pos)); } else pts.push(v3(tr.point));
    }
    const geo = new THREE.BufferGeometry().setFromPoints(pts);
    traces.add(new THREE.Line(geo, new THREE.LineBasicMaterial({ color: 0x222222 })));
  });
  scene.add(traces);

  // Camera: look at the mechanism's middle from an oblique direction.
  function resetView() {
    const c = v3(D.center);
    camera.position.copy(c).add(new THREE.Vector3(1.2, 0.9, 2.2).multiplyScalar(L * 1.6));
    controls.target.copy(c);
    camera.lookAt(c);
    controls.update();
  }

  // Controls.
  const slider = document.getElementById("time"), clock = document.getElementById("clock");
  const playBtn = document.getElementById("play"), speedSel = document.getElementById("speed"), loopBox = document.getElementById("loop");
  let playing = false, lastWall = 0;
  playBtn.onclick = function () { playing = !playing; playBtn.textContent = playing ? "pause" : "play"; lastWall = performance.now(); };
  slider.oninput = function () { playing = false; playBtn.textContent = "play"; setTime(T[0] + (T[n - 1] - T[0]) * Number(slider.value) / 1000); };
  document.getElementById("reset").onclick = resetView;
  document.getElementById("traces").onchange = function (e) { traces.visible = e.target.checked; };
  const label = document.getElementById("label");
  document.getElementById("labels").onchange = function (e) { label.hidden = !e.target.checked; };
  const ray = new THREE.Raycaster(), mouse = new THREE.Vector2();
  renderer.domElement.addEventListener("mousemove", function (e) {
    const r = renderer.domElement.getBoundingClientRect();
    mouse.set(((e.clientX - r.left) / r.width) * 2 - 1, -((e.clientY - r.top) / r.height) * 2 + 1);
    ray.setFromCamera(mouse, camera);
    const hit = ray.intersectObjects(pickable, false)[0];
    label.textContent = hit ? hit.object.userData.label : "";
    label.style.left = (e.clientX + 12) + "px";
    label.style.top = (e.clientY + 12) + "px";
  });

  // Plots: SVG, several columns against time or against any column (a driver's
  // value, say), a cursor, stop marks.
  const plots = (function () {
    const svg = document.getElementById("plot"), pick = document.getElementById("columns"), xsel = document.getElementById("xaxis");
    function title(s) { return s.name + (s.unit ? " [" + s.unit + "]" : ""); }
    D.series.forEach(function (s, i) { const o = document.createElement("option"); o.value = i; o.textContent = title(s); pick.appendChild(o); });
    { const o = document.createElement("option"); o.value = -1; o.textContent = "t [s]"; xsel.appendChild(o); }
    D.series.forEach(function (s, i) { const o = document.createElement("option"); o.value = i; o.textContent = title(s); xsel.appendChild(o); });
    const defaults = D.series.map(function (s, i) { return i; }).filter(function (i) { return D.series[i].default; }).slice(0, 1);
    Array.prototype.forEach.call(pick.options, function (o) { o.selected = defaults.indexOf(Number(o.value)) >= 0; });
    const W = 480, H = 260, M = 44, ns = "http://www.w3.org/2000/svg";
    let cursorLine = null;
    function el(name, attrs) { const e = document.createElementNS(ns, name); for (const k in attrs) e.setAttribute(k, attrs[k]); return e; }
    let xs = T, xlo = T[0], xhi = T[n - 1];
    function Xv(v) { return M + (W - M - 8) * (v - xlo) / Math.max(xhi - xlo, 1e-300); }
    function rowAt(t) { let k = 0; while (k + 1 < n && T[k + 1] <= t) ++k; return k; }
    // Time maps straight onto a time axis; on a column's axis, through the row at that time.
    function X(t) { return xs === T ? Xv(t) : Xv(xs[rowAt(t)]); }
    function draw() {
      while (svg.firstChild) svg.removeChild(svg.firstChild);
      xs = Number(xsel.value) < 0 ? T : D.series[Number(xsel.value)].values;
      xlo = Infinity; xhi = -Infinity;
      xs.forEach(function (v) { if (isFinite(v)) { xlo = Math.min(xlo, v); xhi = Math.max(xhi, v); } });
      if (!(xhi > xlo)) { xlo -= 1; xhi += 1; }
      const chosen = Array.prototype.filter.call(pick.options, function (o) { return o.selected; }).map(function (o) { return D.series[Number(o.value)]; });
      let lo = Infinity, hi = -Infinity;
      chosen.forEach(function (s) { s.values.forEach(function (v) { if (isFinite(v)) { lo = Math.min(lo, v); hi = Math.max(hi, v); } }); });
      if (!(hi > lo)) { lo -= 1; hi += 1; }
      const Y = function (v) { return H - 24 - (H - 34) * (v - lo) / (hi - lo); };
      svg.appendChild(el("rect", { x: M, y: 10, width: W - M - 8, height: H - 34, fill: "white", stroke: "#ccc" }));
      svg.appendChild(el("text", { x: 4, y: 18, "font-size": 10 }).appendChild(document.createTextNode(hi.toPrecision(4))).parentNode);
      svg.appendChild(el("text", { x: 4, y: H - 24, "font-size": 10 }).appendChild(document.createTextNode(lo.toPrecision(4))).parentNode);
      svg.appendChild(el("text", { x: W / 2, y: H - 6, "font-size": 10 }).appendChild(document.createTextNode(xsel.options[xsel.selectedIndex].textContent)).parentNode);
      chosen.forEach(function (s, i) {
        let d = "";
        s.values.forEach(function (v, k) { if (isFinite(v) && isFinite(xs[k])) d += (d ? "L" : "M") + Xv(xs[k]).toFixed(1) + "," + Y(v).toFixed(1); });
        svg.appendChild(el("path", { d: d, fill: "none", stroke: "#" + palette[i % palette.length].toString(16).padStart(6, "0"), "stroke-width": 1.5 }));
      });
      D.marks.forEach(function (m) { svg.appendChild(el("line", { x1: X(m.t), x2: X(m.t), y1: 10, y2: H - 24, stroke: "red", "stroke-dasharray": "4 2" })); });
      cursorLine = el("line", { x1: 0, x2: 0, y1: 10, y2: H - 24, stroke: "#333" });
      svg.appendChild(cursorLine);
      cursor(current);
    }
    function cursor(t) { if (cursorLine) { cursorLine.setAttribute("x1", X(t)); cursorLine.setAttribute("x2", X(t)); } }
    pick.onchange = draw;
    xsel.onchange = draw;
    return { draw: draw, cursor: cursor, xaxis: xsel };
  })();

  function resize() {
    const w = view.clientWidth, h = view.clientHeight;
    renderer.setSize(w, h);
    camera.aspect = w / h;
    camera.updateProjectionMatrix();
  }
  window.addEventListener("resize", resize);

  let probe = -1;
  function tick(now) {
    // The layout can settle after the first frame (fonts, scrollbars): follow it.
    const size = renderer.getSize(new THREE.Vector2());
    if (size.x !== view.clientWidth || size.y !== view.clientHeight) resize();
    if (playing) {
      const dt = (now - lastWall) / 1000 * Number(speedSel.value);
      let t = current + dt;
      if (t > T[n - 1]) { if (loopBox.checked) t = T[0]; else { t = T[n - 1]; playing = false; playBtn.textContent = "play"; } }
      setTime(t);
    }
    lastWall = now;
    controls.update();
    renderer.render(scene, camera);
    if (probe >= 0) reportProbe(probe);
    requestAnimationFrame(tick);
  }
  // Where the middle of a body's first bar is drawn, for the pixel test.
  function reportProbe(b) {
    const pts = D.bodies[b].points, mid = pts.length > 1 ? pts[0].map(function (x, a) { return (x + pts[1][a]) / 2; }) : pts[0];
    const px = window.mechkin.project(b, mid), r = renderer.domElement.getBoundingClientRect();
    // The pixel actually drawn there, read back from the canvas (WebGL rows count from the bottom).
    const gl = renderer.getContext(), rgba = new Uint8Array(4);
    gl.readPixels(Math.round(px[0] - r.left), Math.round(r.height - (px[1] - r.top)), 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, rgba);
    document.body.setAttribute("data-probe", px[0].toFixed(1) + "," + px[1].toFixed(1) + "," +
      window.mechkin.color(b).toString(16).padStart(6, "0") + "," + rgba[0] + "," + rgba[1] + "," + rgba[2]);
  }

  // Test hooks: set the time, and project a body point to page pixels.
  window.mechkin = {
    setTime: function (t) { playing = false; setTime(t); renderer.render(scene, camera); },
    project: function (body, local) {
      const p = globalPoint(body, local, new THREE.Vector3()).project(camera), r = renderer.domElement.getBoundingClientRect();
      return [r.left + (p.x + 1) / 2 * r.width, r.top + (1 - p.y) / 2 * r.height];
    },
    color: function (body) { return groups[body].userData.color; }
  };

  resize();
  resetView();
  plots.draw();
  const hash = new URLSearchParams(location.hash.slice(1));
  if (hash.has("x")) {  // #x=NAME: plot against that column
    Array.prototype.forEach.call(plots.xaxis.options, function (o, i) { if (o.textContent.split(" [")[0] === hash.get("x")) plots.xaxis.selectedIndex = i; });
    plots.draw();
  }
  setTime(hash.has("t") ? Number(hash.get("t")) : T[0]);
  if (hash.has("play")) playBtn.onclick();
  renderer.render(scene, camera);
  if (hash.has("probe")) { probe = Number(hash.get("probe")); reportProbe(probe); }
  status.textContent = D.stop.complete ? "" : "run stopped at t = " + D.stop.t + " s: " + D.stop.message;
  flushErrors();
  document.body.setAttribute("data-ready", "1");
  requestAnimationFrame(tick);
})();
