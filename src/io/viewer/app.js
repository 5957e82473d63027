// mechkin view: the page's program. Reads window.MECHKIN_DATA (written by
// src/io/viewer.cpp), draws each body as a stick figure of its joint and output
// points with joint glyphs by type, animates the table's poses (interpolated in
// time, playing in a loop unless the address has #paused or #t=), draws output
// points' paths fading with time (coupler curves), frames the mechanism's whole
// motion with standard views (front, side, top, iso; perspective or
// orthographic; up = the data's up axis), and plots columns in panels, one per
// unit, with ticks, grids, legends, a cursor readout and the marked events;
// clearance outputs' closest points are marked and touching bodies' shapes drawn red.
// Test hooks: window.mechkin and the address fragment (#t= #paused #view= #ortho
// #x= #probe= #export=).
(function () {
  "use strict";
  const D = window.MECHKIN_DATA;
  const status = document.getElementById("status");
  const errors = window.MECHKIN_ERRORS || [];
  function flushErrors() { if (errors.length) document.body.setAttribute("data-errors", errors.join(" | ")); }
  const hash = new URLSearchParams(location.hash.slice(1));
  const svgNs = "http://www.w3.org/2000/svg";

  const view = document.getElementById("view");
  const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  const background = new THREE.Color(0xf4f4f4);
  renderer.setPixelRatio(1);
  renderer.setClearColor(background);
  view.appendChild(renderer.domElement);
  const scene = new THREE.Scene();
  const L = D.size > 0 ? D.size : 1;
  function v3(a) { return new THREE.Vector3(a[0], a[1], a[2]); }
  const up = v3(D.up).normalize();
  const boxLo = v3(D.bounds.lo), boxHi = v3(D.bounds.hi);
  const boxSize = Math.max(new THREE.Vector3().subVectors(boxHi, boxLo).length(), L * 1e-3);
  // Two cameras sharing the up axis, each with its own controls (OrbitControls
  // takes the up axis when it is made); one of them is active.
  const perspective = new THREE.PerspectiveCamera(35, 1, boxSize * 1e-3, boxSize * 1e3);
  const orthographic = new THREE.OrthographicCamera(-1, 1, 1, -1, -boxSize * 1e3, boxSize * 1e3);
  perspective.up.copy(up);
  orthographic.up.copy(up);
  const controlsOf = new Map();
  [perspective, orthographic].forEach(function (c) {
    const k = new THREE.OrbitControls(c, renderer.domElement);
    k.enabled = false;
    controlsOf.set(c, k);
  });
  let camera = perspective, controls = controlsOf.get(camera);
  controls.enabled = true;
  scene.add(new THREE.HemisphereLight(0xffffff, 0x808080, 0.9));
  const sun = new THREE.DirectionalLight(0xffffff, 0.6);
  sun.position.copy(up).multiplyScalar(2).add(new THREE.Vector3(1, 1, 1));
  scene.add(sun);

  const palette = [0x1f77b4, 0xd62728, 0x2ca02c, 0xff7f0e, 0x9467bd, 0x8c564b, 0xe377c2, 0x17becf, 0xbcbd22, 0x7f7f7f];
  function hex(c) { return "#" + c.toString(16).padStart(6, "0"); }
  const thick = Math.min(L, boxSize) * 0.02;
  function material(color) { return new THREE.MeshLambertMaterial({ color: color }); }
  function stick(a, b, r, mat) {
    const d = new THREE.Vector3().subVectors(b, a), len = d.length();
    const m = new THREE.Mesh(new THREE.CylinderBufferGeometry(r, r, Math.max(len, 1e-9), 12), mat);
    m.position.copy(a).add(b).multiplyScalar(0.5);
    if (len > 0) m.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), d.normalize());
    return m;
  }
  function ball(p, r, mat) { const m = new THREE.Mesh(new THREE.SphereBufferGeometry(r, 16, 12), mat); m.position.copy(p); return m; }

  // The user's own geometry (a body's shape and shapes, ground's shapes), semi-transparent
  // over the sticks; a mesh (or a convex hull's faces) as its triangles, flat-shaded.
  const shapesOf = new Map();  // body index (ground −1) → its shape meshes
  function shapeMesh(sh, color) {
    const sm = new THREE.MeshLambertMaterial({ color: color, transparent: true, opacity: 0.45, side: THREE.DoubleSide });
    let geo;
    if (sh.type === "box") geo = new THREE.BoxBufferGeometry(sh.size[0], sh.size[1], sh.size[2]);
    else if (sh.type === "cylinder") geo = new THREE.CylinderBufferGeometry(sh.radius, sh.radius, sh.length, 24);
    else if (sh.type === "mesh") {
      geo = new THREE.BufferGeometry();
      geo.setAttribute("position", new THREE.BufferAttribute(new Float32Array(sh.positions), 3));
      geo.setIndex(sh.triangles);
      geo = geo.toNonIndexed();
      geo.computeVertexNormals();
    } else geo = new THREE.SphereBufferGeometry(sh.radius, 24, 16);
    const mesh = new THREE.Mesh(geo, sm);
    mesh.position.copy(v3(sh.center));
    if (sh.type === "cylinder") mesh.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), v3(sh.axis).normalize());
    mesh.userData.color = color;
    return mesh;
  }

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
    b.shapes.forEach(function (sh) { g.add(shapeMesh(sh, palette[i % palette.length])); });
    g.traverse(function (o) { if (o.isMesh) { o.userData.label = b.name; pickable.push(o); } });
    shapesOf.set(i, g.children.filter(function (o) { return o.userData.color !== undefined; }));
    g.userData.color = palette[i % palette.length];
    scene.add(g);
    groups.push(g);
  });
  const ground = new THREE.Group();
  scene.add(ground);
  shapesOf.set(-1, (D.ground_shapes || []).map(function (sh) {
    const m = shapeMesh(sh, 0x999999);
    m.userData.label = "ground";
    pickable.push(m);
    ground.add(m);
    return m;
  }));
  function parent(body) { return body < 0 ? ground : groups[body]; }

  // Joint glyphs by the joint type's glyph name (src/joints), fixed in body1 (ground parts grey).
  const jointMat = material(0x444444), groundMat = material(0x999999);
  D.joints.forEach(function (j) {
    const o = v3(j.origin), h = v3(j.axis).normalize(), s = thick;
    const mat = j.body1 < 0 ? groundMat : jointMat;
    let glyph;
    if (j.glyph === "pin") glyph = stick(o.clone().addScaledVector(h, -3 * s), o.clone().addScaledVector(h, 3 * s), 1.8 * s, mat);
    else if (j.glyph === "sleeve") glyph = stick(o.clone().addScaledVector(h, -5 * s), o.clone().addScaledVector(h, 5 * s), 1.4 * s, mat);
    else if (j.glyph === "slider") {
      glyph = new THREE.Mesh(new THREE.BoxBufferGeometry(3 * s, 8 * s, 3 * s), mat);
      glyph.position.copy(o);
      glyph.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), h);
    } else if (j.glyph === "ball") glyph = ball(o, 2.2 * s, mat);
    else if (j.glyph === "cross") {
      glyph = new THREE.Group();
      const h2 = v3(j.axis2).normalize();
      glyph.add(stick(o.clone().addScaledVector(h, -3 * s), o.clone().addScaledVector(h, 3 * s), s, mat));
      glyph.add(stick(o.clone().addScaledVector(h2, -3 * s), o.clone().addScaledVector(h2, 3 * s), s, mat));
    } else if (j.glyph === "plate") {
      glyph = new THREE.Mesh(new THREE.BoxBufferGeometry(8 * s, 0.6 * s, 8 * s), mat);
      glyph.position.copy(o);
      glyph.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), h);
    }
    if (glyph) { glyph.traverse(function (x) { if (x.isMesh) { x.userData.label = j.name + " (" + j.type + ")"; pickable.push(x); } }); parent(j.body1).add(glyph); }
  });
  // Ground's points: fixed pivots.
  D.ground.forEach(function (p) { ground.add(ball(v3(p), thick * 1.4, groundMat)); });
  // Distance links and drivers: a thin rod between their two body points, set each frame.
  const linkMat = material(0x555555), yAxis = new THREE.Vector3(0, 1, 0);
  const links = D.joints.filter(function (j) { return j.glyph === "link"; }).concat(D.links).map(function (j) {
    const rod = new THREE.Mesh(new THREE.CylinderBufferGeometry(thick * 0.5, thick * 0.5, 1, 8), linkMat);
    rod.userData.label = j.name;
    pickable.push(rod);
    scene.add(rod);
    return { j: j, rod: rod };
  });
  // Couplers: a dashed line through the origins of the joints each one ties, set each frame.
  const couplerMat = new THREE.LineDashedMaterial({ color: 0xb35900, dashSize: thick * 3, gapSize: thick * 2 });
  const couplers = (D.couplers || []).map(function (c) {
    const geo = new THREE.BufferGeometry();
    geo.setAttribute("position", new THREE.BufferAttribute(new Float32Array(3 * c.joints.length), 3));
    const line = new THREE.Line(geo, couplerMat);
    line.userData.label = c.name + " (" + c.type + ")";
    scene.add(line);
    return { c: c, line: line };
  });
  // Clearance outputs: the two closest points (small balls) and the line between them,
  // per frame from the table's columns; where the bodies touch, their shapes turn red.
  const markMat = material(0x222222), touchColor = 0xff0000;
  const clearances = (D.clearances || []).map(function (c) {
    const balls = [ball(new THREE.Vector3(), thick * 0.7, markMat), ball(new THREE.Vector3(), thick * 0.7, markMat)];
    const geo = new THREE.BufferGeometry();
    geo.setAttribute("position", new THREE.BufferAttribute(new Float32Array(6), 3));
    const line = new THREE.Line(geo, new THREE.LineBasicMaterial({ color: 0x222222 }));
    balls.concat([line]).forEach(function (o) { o.userData.label = c.name; scene.add(o); });
    // In contact from each located first contact until a row is clear again.
    const spans = c.contacts.map(function (h) {
      let end = Infinity;
      for (let k = 0; k < D.times.length; ++k) if (D.times[k] > h.t && c.distance[k] > 0) { end = D.times[k]; break; }
      return [h.t, end];
    });
    return { c: c, balls: balls, line: line, spans: spans };
  });
  function setClearances(k, u) {
    const touching = new Set(), report = [], inContact = [];
    clearances.forEach(function (cl) {
      const P = cl.c.points, d = cl.c.distance, k1 = u > 0 && k + 1 < n ? k + 1 : k, w = k1 === k ? 0 : u;
      const attr = cl.line.geometry.attributes.position;
      for (let s = 0; s < 2; ++s) {
        const a = 6 * k + 3 * s, b = 6 * k1 + 3 * s;
        cl.balls[s].position.set(P[a] + w * (P[b] - P[a]), P[a + 1] + w * (P[b + 1] - P[a + 1]), P[a + 2] + w * (P[b + 2] - P[a + 2]));
        attr.setXYZ(s, cl.balls[s].position.x, cl.balls[s].position.y, cl.balls[s].position.z);
      }
      attr.needsUpdate = true;
      cl.line.geometry.computeBoundingSphere();
      const contact = cl.spans.some(function (sp) { return current >= sp[0] && current < sp[1]; }) || (d[k] <= 0 && d[k1] <= 0);
      if (contact) { touching.add(cl.c.body1); touching.add(cl.c.body2); inContact.push(cl.c.name); }
      report.push(cl.c.name + ":" + cl.balls.map(function (m) { return m.position.toArray().map(function (x) { return x.toPrecision(12); }).join(","); }).join(","));
    });
    shapesOf.forEach(function (meshes, body) {
      meshes.forEach(function (m) { m.material.color.setHex(touching.has(body) ? touchColor : m.userData.color); });
    });
    // Test hooks: the marks as drawn, the outputs in contact and the bodies drawn red.
    document.body.setAttribute("data-clearance", report.join(";"));
    document.body.setAttribute("data-contact", inContact.join(","));
    document.body.setAttribute("data-red-bodies", Array.from(touching).sort(function (a, b) { return a - b; }).join(","));
  }
  scene.add(new THREE.AxesHelper(L * 0.3));
  // The floor: a grid across the up axis, under the whole motion's box.
  const boxCenter = new THREE.Vector3().addVectors(boxLo, boxHi).multiplyScalar(0.5);
  const grid = new THREE.GridHelper(boxSize * 2, 20, 0xbbbbbb, 0xdddddd);
  grid.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), up);
  {
    let low = Infinity;
    boxCorners().forEach(function (c) { low = Math.min(low, c.dot(up)); });
    grid.position.copy(boxCenter).addScaledVector(up, low - boxCenter.dot(up) - 0.05 * boxSize);
  }
  scene.add(grid);
  function boxCorners() {
    const out = [];
    for (let k = 0; k < 8; ++k) out.push(new THREE.Vector3(k & 1 ? boxHi.x : boxLo.x, k & 2 ? boxHi.y : boxLo.y, k & 4 ? boxHi.z : boxLo.z));
    return out;
  }

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
      const d = new THREE.Vector3().subVectors(b, a), len = d.length();
      l.rod.position.copy(a).add(b).multiplyScalar(0.5);
      l.rod.scale.set(1, Math.max(len, 1e-9), 1);
      if (len > 0) l.rod.quaternion.setFromUnitVectors(yAxis, d.divideScalar(len));
    });
    couplers.forEach(function (cl) {
      const attr = cl.line.geometry.attributes.position, p = new THREE.Vector3();
      cl.c.joints.forEach(function (k, i) {
        const j = D.joints[k];
        globalPoint(j.body1, j.origin, p);
        attr.setXYZ(i, p.x, p.y, p.z);
      });
      attr.needsUpdate = true;
      cl.line.geometry.computeBoundingSphere();
      cl.line.computeLineDistances();
    });
    setClearances(k, u);
    slider.value = String(Math.round(1000 * (current - T[0]) / Math.max(T[n - 1] - T[0], 1e-300)));
    clock.textContent = "t = " + current.toPrecision(6) + " s";
    paths.fade(k);
    plots.cursor(current);
  }

  // Paths of output points over the whole motion (coupler curves): the part
  // already travelled bright and fading with its age, the rest faint.
  const paths = (function () {
    const group = new THREE.Group(), lines = [];
    function fill(tr, xyz) {  // the trace's points from the poses (again after a live re-solve)
      const pos = new THREE.Vector3(), q = new THREE.Quaternion();
      for (let k = 0; k < n; ++k) {
        const p = v3(tr.point);
        if (tr.body >= 0) { pose(tr.body, k, pos, q); p.applyQuaternion(q).add(pos); }
        xyz[3 * k] = p.x; xyz[3 * k + 1] = p.y; xyz[3 * k + 2] = p.z;
      }
      return xyz;
    }
    D.traces.forEach(function (tr, i) {
      const xyz = fill(tr, new Float32Array(3 * n));
      const geo = new THREE.BufferGeometry();
      geo.setAttribute("position", new THREE.BufferAttribute(xyz, 3));
      geo.setAttribute("color", new THREE.BufferAttribute(new Float32Array(3 * n), 3));
      const color = new THREE.Color(i ? palette[(i + 5) % palette.length] : 0x111111);
      const line = new THREE.Line(geo, new THREE.LineBasicMaterial({ vertexColors: THREE.VertexColors }));
      lines.push({ line: line, color: color, trace: tr });
      group.add(line);
    });
    const span = Math.max(T[n - 1] - T[0], 1e-300), mix = new THREE.Color();
    function fade(k) {
      lines.forEach(function (l) {
        const c = l.line.geometry.attributes.color;
        for (let m = 0; m < n; ++m) {
          const age = m <= k ? T[k] - T[m] : span - (T[m] - T[k]);  // the motion loops: the rest is last lap's
          const w = 0.25 + 0.75 * Math.exp(-3 * age / span);
          mix.copy(background).lerp(l.color, w);
          c.setXYZ(m, mix.r, mix.g, mix.b);
        }
        c.needsUpdate = true;
      });
    }
    function refill() {
      lines.forEach(function (l) {
        const attr = l.line.geometry.attributes.position;
        fill(l.trace, attr.array);
        attr.needsUpdate = true;
        l.line.geometry.computeBoundingSphere();
      });
    }
    scene.add(group);
    return { group: group, fade: fade, refill: refill };
  })();

  // Standard views: right-handed (right, up, back) axes for the up axis; y-up
  // looks from +z at the front, z-up from −y (as CAD and Blender do).
  const frameAxes = (function () {
    const a = [Math.abs(up.x), Math.abs(up.y), Math.abs(up.z)], main = a.indexOf(Math.max.apply(null, a));
    const right = [new THREE.Vector3(0, 1, 0), new THREE.Vector3(1, 0, 0), new THREE.Vector3(1, 0, 0)][main];
    right.addScaledVector(up, -right.dot(up)).normalize();
    const back = new THREE.Vector3().crossVectors(right, up).normalize();
    return { right: right, back: back };
  })();
  const views = {
    front: function () { return frameAxes.back.clone(); },
    side: function () { return frameAxes.right.clone(); },
    top: function () { return up.clone().addScaledVector(frameAxes.back, 1e-3).normalize(); },
    iso: function () { return frameAxes.right.clone().add(frameAxes.back).add(up).normalize(); },
  };
  let direction = views.iso();  // from the target towards the camera
  if (D.planar) {  // a planar motion reads best square on: along its plane's normal
    direction = v3(D.planar).normalize();
    if (direction.dot(frameAxes.back) + 1e-3 * direction.dot(up) < 0) direction.negate();
    if (Math.abs(direction.dot(up)) > 0.999) direction.addScaledVector(frameAxes.back, 1e-3).normalize();
  }

  // Fit: the camera looks along `direction` at the whole motion's box, as close as
  // lets every corner in with a margin (orthographic: the frustum around them).
  function fit() {
    const aspect = Math.max(view.clientWidth, 1) / Math.max(view.clientHeight, 1);
    const back = direction.clone().normalize(), right = new THREE.Vector3().crossVectors(up, back);
    if (right.lengthSq() < 1e-12) right.copy(frameAxes.right);
    right.normalize();
    const upward = new THREE.Vector3().crossVectors(back, right);
    const corners = boxCorners();
    let xlo = Infinity, xhi = -Infinity, ylo = Infinity, yhi = -Infinity;
    corners.forEach(function (c) {
      const x = c.clone().sub(boxCenter).dot(right), y = c.clone().sub(boxCenter).dot(upward);
      xlo = Math.min(xlo, x); xhi = Math.max(xhi, x); ylo = Math.min(ylo, y); yhi = Math.max(yhi, y);
    });
    const target = boxCenter.clone().addScaledVector(right, (xlo + xhi) / 2).addScaledVector(upward, (ylo + yhi) / 2);
    const margin = 1.12, halfW = Math.max((xhi - xlo) / 2, boxSize * 0.02), halfH = Math.max((yhi - ylo) / 2, boxSize * 0.02);
    const ty = Math.tan(perspective.fov * Math.PI / 360), tx = ty * aspect;
    let dist = 0;
    corners.forEach(function (c) {
      const d = c.clone().sub(target), z = d.dot(back);
      dist = Math.max(dist, z + margin * Math.abs(d.dot(right)) / tx, z + margin * Math.abs(d.dot(upward)) / ty);
    });
    perspective.position.copy(target).addScaledVector(back, dist);
    perspective.near = dist * 1e-3; perspective.far = dist * 10 + boxSize * 10;
    const h = margin * Math.max(halfH, halfW / aspect);
    Object.assign(orthographic, { left: -h * aspect, right: h * aspect, top: h, bottom: -h, zoom: 1 });
    orthographic.position.copy(target).addScaledVector(back, boxSize * 4);
    [perspective, orthographic].forEach(function (c) {
      c.aspect = aspect;
      c.lookAt(target);
      c.updateProjectionMatrix();
      controlsOf.get(c).target.copy(target);
      controlsOf.get(c).update();
    });
  }
  function setView(name) { direction = views[name](); fit(); }
  function setOrtho(on) {
    controls.enabled = false;
    camera = on ? orthographic : perspective;
    controls = controlsOf.get(camera);
    controls.enabled = true;
    orthoBox.checked = on;
    document.body.setAttribute("data-camera", on ? "orthographic" : "perspective");
  }

  // Controls.
  const slider = document.getElementById("time"), clock = document.getElementById("clock");
  const playBtn = document.getElementById("play"), speedSel = document.getElementById("speed"), loopBox = document.getElementById("loop");
  const orthoBox = document.getElementById("ortho");
  let playing = false, lastWall = 0;
  function setPlaying(on) { playing = on; playBtn.textContent = playing ? "pause" : "play"; lastWall = performance.now(); }
  playBtn.onclick = function () { setPlaying(!playing); };
  slider.oninput = function () { setPlaying(false); setTime(T[0] + (T[n - 1] - T[0]) * Number(slider.value) / 1000); };
  document.getElementById("fit").onclick = fit;
  ["front", "side", "top", "iso"].forEach(function (v) { document.getElementById("v-" + v).onclick = function () { setView(v); }; });
  orthoBox.onchange = function () { setOrtho(orthoBox.checked); };
  document.getElementById("traces").onchange = function (e) { paths.group.visible = e.target.checked; };
  const label = document.getElementById("label");
  document.getElementById("labels").onchange = function (e) { label.hidden = !e.target.checked; };
  const keys = { f: function () { setView("front"); }, s: function () { setView("side"); }, t: function () { setView("top"); },
    i: function () { setView("iso"); }, a: fit, o: function () { setOrtho(camera !== orthographic); }, " ": function () { setPlaying(!playing); } };
  window.addEventListener("keydown", function (e) {
    if (e.target.tagName === "INPUT" || e.target.tagName === "SELECT" || e.ctrlKey || e.metaKey || e.altKey || !keys[e.key]) return;
    keys[e.key]();
    e.preventDefault();
  });
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

  const plots = makePlots();

  function resize() {
    const w = view.clientWidth, h = view.clientHeight;
    renderer.setSize(w, h);
    fit();
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
      if (t > T[n - 1]) { if (loopBox.checked) t = T[0]; else { t = T[n - 1]; setPlaying(false); } }
      setTime(t);
    }
    lastWall = now;
    // The test hook for "opens playing": the time shown and whether it plays, read
    // from the DOM instead of from how many pixels moved in a wall-clock window.
    document.body.setAttribute("data-time", current.toPrecision(9));
    document.body.setAttribute("data-playing", playing ? "1" : "0");
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

  // Test hooks: set the time, project a body point to page pixels, the exports.
  window.mechkin = {
    setTime: function (t) { setPlaying(false); setTime(t); renderer.render(scene, camera); },
    project: function (body, local) {
      const p = globalPoint(body, local, new THREE.Vector3()).project(camera), r = renderer.domElement.getBoundingClientRect();
      return [r.left + (p.x + 1) / 2 * r.width, r.top + (1 - p.y) / 2 * r.height];
    },
    color: function (body) { return groups[body].userData.color; },
    view: setView, ortho: setOrtho, fit: fit, svg: plots.svgText, csv: plots.csvText,
    // The live page (live.js) changed D's poses, times and series in place: redraw all.
    refresh: function () { paths.refill(); plots.draw(); setTime(current); renderer.render(scene, camera); },
    time: function () { return current; },
  };

  // Plot helpers.
  function title(s) { return s.name + (s.unit ? " [" + s.unit + "]" : ""); }
  function el(name, attrs, text) {
    const e = document.createElementNS(svgNs, name);
    for (const k in attrs) e.setAttribute(k, attrs[k]);
    if (text !== undefined) e.appendChild(document.createTextNode(text));
    return e;
  }
  function range(values, out) {
    values.forEach(function (v) { if (isFinite(v)) { out[0] = Math.min(out[0], v); out[1] = Math.max(out[1], v); } });
    return out;
  }
  // Round tick steps (1, 2, 5 × 10^k), about `count` across [lo, hi].
  function ticks(lo, hi, count) {
    const raw = (hi - lo) / count, mag = Math.pow(10, Math.floor(Math.log10(raw)));
    const step = [1, 2, 5, 10].map(function (f) { return f * mag; }).find(function (s) { return s >= raw; });
    const out = [], digits = Math.max(0, -Math.floor(Math.log10(step) + 1e-9));
    for (let v = Math.ceil(lo / step - 1e-9) * step; v <= hi + step * 1e-9; v += step)
      out.push({ v: v, text: Math.abs(v) >= 1e6 ? v.toExponential(2) : (Math.abs(v) < step * 1e-6 ? 0 : v).toFixed(Math.min(digits, 10)) });
    return out;
  }
  function padded(r) {
    if (!(r[1] > r[0])) { const m = Math.abs(r[0]) * 0.05 || 1; return [r[0] - m, r[0] + m]; }
    const m = 0.04 * (r[1] - r[0]);
    return [r[0] - m, r[1] + m];
  }
  function download(text, type, name) {
    const a = document.createElement("a");
    a.href = URL.createObjectURL(new Blob([text], { type: type }));
    a.download = name;
    document.body.appendChild(a);
    a.click();
    setTimeout(function () { URL.revokeObjectURL(a.href); a.remove(); }, 1000);
  }
  // The page's table (decimated as the page is) with the table's headers.
  function csvText() {
    const head = ["t [s]"].concat(D.series.map(title)).map(function (h) { return /[",]/.test(h) ? '"' + h.replace(/"/g, '""') + '"' : h; });
    const lines = [head.join(",")];
    for (let k = 0; k < n; ++k) lines.push([T[k]].concat(D.series.map(function (s) { return s.values[k] === null ? "" : s.values[k]; })).join(","));
    return lines.join("\n") + "\n";
  }

  // One panel: its frame, ticks and grid on both axes, unit, series, legend, marks and cursor.
  function drawPanel(members, index, W, H, axis) {
    const M = { l: 62, r: 18, t: 12 + 16 * Math.ceil(members.length / 2), b: 36 };
    const svg = el("svg", { xmlns: svgNs, width: W, height: H, viewBox: "0 0 " + W + " " + H, "font-family": "sans-serif", "font-size": 11, class: "plot" });
    const yr = padded(members.reduce(function (r, i) { return range(D.series[i].values, r); }, [Infinity, -Infinity]));
    const X = function (v) { return M.l + (W - M.l - M.r) * (v - axis.lo) / (axis.hi - axis.lo); };
    const Y = function (v) { return H - M.b - (H - M.t - M.b) * (v - yr[0]) / (yr[1] - yr[0]); };
    svg.appendChild(el("rect", { x: M.l, y: M.t, width: W - M.l - M.r, height: H - M.t - M.b, fill: "white", stroke: "#999" }));
    const unit = D.series[members[0]].unit;
    ticks(yr[0], yr[1], Math.max(3, Math.floor((H - M.t - M.b) / 40))).forEach(function (k) {
      svg.appendChild(el("line", { x1: M.l, x2: W - M.r, y1: Y(k.v), y2: Y(k.v), stroke: "#e4e4e4", class: "grid" }));
      svg.appendChild(el("text", { x: M.l - 4, y: Y(k.v) + 4, "text-anchor": "end", class: "tick" }, k.text));
    });
    ticks(axis.lo, axis.hi, 6).forEach(function (k) {
      svg.appendChild(el("line", { x1: X(k.v), x2: X(k.v), y1: M.t, y2: H - M.b, stroke: "#e4e4e4", class: "grid" }));
      svg.appendChild(el("text", { x: X(k.v), y: H - M.b + 14, "text-anchor": "middle", class: "tick" }, k.text));
    });
    svg.appendChild(el("text", { x: 12, y: (M.t + H - M.b) / 2, transform: "rotate(-90 12 " + (M.t + H - M.b) / 2 + ")", "text-anchor": "middle" },
      unit ? "[" + unit + "]" : "value"));
    svg.appendChild(el("text", { x: (M.l + W - M.r) / 2, y: H - 4, "text-anchor": "middle" }, axis.label));
    const values = [];
    members.forEach(function (si, i) {
      const s = D.series[si], color = hex(palette[(index * 3 + i) % palette.length]);
      let d = "";
      s.values.forEach(function (v, k) { if (isFinite(v) && isFinite(axis.xs[k])) d += (d ? "L" : "M") + X(axis.xs[k]).toFixed(1) + "," + Y(v).toFixed(1); });
      svg.appendChild(el("path", { d: d, fill: "none", stroke: color, "stroke-width": 1.6, class: "series", "data-name": s.name }));
    });
    members.forEach(function (si, i) {  // the legend, two entries a row, each with the value at the cursor
      const s = D.series[si], color = hex(palette[(index * 3 + i) % palette.length]);
      const lx = M.l + (i % 2) * (W - M.l - M.r) / 2, ly = 12 + 16 * Math.floor(i / 2);
      svg.appendChild(el("line", { x1: lx, x2: lx + 16, y1: ly - 4, y2: ly - 4, stroke: color, "stroke-width": 3 }));
      const legend = el("text", { x: lx + 20, y: ly, class: "legend" }, title(s));
      const value = el("tspan", { class: "value", "font-weight": "bold" }, "");
      legend.appendChild(value);
      svg.appendChild(legend);
      values.push({ s: s, node: value });
    });
    D.marks.forEach(function (m) {
      const line = el("line", { x1: 0, x2: 0, y1: M.t, y2: H - M.b, stroke: m.kind === "reselection" ? "#e08000" : "red",
        "stroke-dasharray": "4 2", class: "mark mark-" + m.kind, "data-t": m.t });
      line.appendChild(el("title", {}, m.label + " at t = " + m.t + " s"));
      svg.appendChild(line);
    });
    const cursorLine = el("line", { x1: 0, x2: 0, y1: M.t, y2: H - M.b, stroke: "#333", class: "cursor" });
    svg.appendChild(cursorLine);
    return { svg: svg, X: X, marks: svg.querySelectorAll(".mark"), cursorLine: cursorLine, values: values };
  }

  // Plots: panels of columns (one axis and unit each) against time or any
  // column, with ticks and grids on both axes, a legend with the values at the
  // cursor, the events of the run marked, each downloadable as SVG.
  function makePlots() {
    const side = document.getElementById("panels"), pick = document.getElementById("columns"), xsel = document.getElementById("xaxis");
    const byName = new Map(D.series.map(function (s, i) { return [s.name, i]; }));
    D.series.forEach(function (s, i) { const o = document.createElement("option"); o.value = i; o.textContent = title(s); pick.appendChild(o); });
    { const o = document.createElement("option"); o.value = -1; o.textContent = "t [s]"; xsel.appendChild(o); }
    D.series.forEach(function (s, i) { const o = document.createElement("option"); o.value = i; o.textContent = title(s); xsel.appendChild(o); });
    let panels = D.plots.map(function (p) { return p.map(function (name) { return byName.get(name); }).filter(function (i) { return i !== undefined; }); })
      .filter(function (p) { return p.length; });
    Array.prototype.forEach.call(pick.options, function (o) { o.selected = panels.some(function (p) { return p.indexOf(Number(o.value)) >= 0; }); });
    let drawn = [], xs = T, xlo = T[0], xhi = T[n - 1];
    function rowAt(t) { return frameAt(t)[0]; }
    function draw() {
      while (side.firstChild) side.removeChild(side.firstChild);
      xs = Number(xsel.value) < 0 ? T : D.series[Number(xsel.value)].values;
      // Against time: the run's span and the marks (a stop lies a little after the last row).
      const xr = Number(xsel.value) < 0 ? range(D.marks.map(function (m) { return m.t; }), [T[0], T[n - 1]])
        : padded(range(xs, [Infinity, -Infinity]));
      xlo = xr[0]; xhi = xr[1] > xr[0] ? xr[1] : xr[0] + 1;
      const W = Math.max(320, side.clientWidth - 4);
      const H = Math.max(180, Math.min(320, Math.floor((side.clientHeight - 8) / Math.max(panels.length, 1)) - 26));
      drawn = panels.map(function (members, p) {
        const d = drawPanel(members, p, W, H, { xs: xs, lo: xlo, hi: xhi, label: xsel.options[xsel.selectedIndex].textContent }), box = document.createElement("div"), head = document.createElement("div");
        box.className = "panel";
        const save = document.createElement("a");
        save.textContent = "SVG";
        save.href = "#";
        save.title = "download this plot as SVG";
        save.onclick = function (e) { e.preventDefault(); download(svgText(p), "image/svg+xml", plotFileName(p) + ".svg"); };
        head.appendChild(save);
        box.appendChild(head);
        box.appendChild(d.svg);
        side.appendChild(box);
        return d;
      });
      cursor(current);
    }
    function X(d, t) { return xs === T ? d.X(t) : d.X(xs[rowAt(t)]); }
    function cursor(t) {
      const k = frameAt(t), row = k[1] > 0.5 && k[0] + 1 < n ? k[0] + 1 : k[0];
      drawn.forEach(function (d) {
        d.cursorLine.setAttribute("x1", X(d, t)); d.cursorLine.setAttribute("x2", X(d, t));
        d.marks.forEach(function (m) { const x = X(d, Number(m.getAttribute("data-t"))); m.setAttribute("x1", x); m.setAttribute("x2", x); });
        d.values.forEach(function (v) { const y = v.s.values[row]; v.node.textContent = " = " + (isFinite(y) ? Number(y.toPrecision(5)) : "—"); });
      });
    }
    function plotFileName(p) { return (D.name || "mechanism").replace(/[^\w.-]+/g, "_") + "-plot" + (p + 1); }
    function svgText(p) { return '<?xml version="1.0" encoding="UTF-8"?>\n' + new XMLSerializer().serializeToString(drawn[p].svg); }
    document.getElementById("csv").onclick = function (e) { e.preventDefault(); download(csvText(), "text/csv", plotFileName(0).replace(/-plot1$/, "") + ".csv"); };
    // Choosing columns by hand: one panel per unit, in the menu's order.
    pick.onchange = function () {
      const units = [];
      panels = [];
      Array.prototype.forEach.call(pick.options, function (o) {
        if (!o.selected) return;
        const i = Number(o.value), u = units.indexOf(D.series[i].unit);
        if (u < 0) { units.push(D.series[i].unit); panels.push([i]); } else panels[u].push(i);
      });
      draw();
    };
    xsel.onchange = draw;
    return { draw: draw, cursor: cursor, xaxis: xsel, svgText: svgText, csvText: csvText };
  }

  resize();
  setOrtho(!!D.planar);
  if (hash.has("view")) setView(hash.get("view"));
  if (hash.has("ortho")) setOrtho(hash.get("ortho") !== "0");
  plots.draw();
  if (hash.has("x")) {  // #x=NAME: plot against that column
    Array.prototype.forEach.call(plots.xaxis.options, function (o, i) { if (o.textContent.split(" [")[0] === hash.get("x")) plots.xaxis.selectedIndex = i; });
    plots.draw();
  }
  // Opens playing in a loop; #paused, the file's "view": {"paused": true}, or a time asked for (#t=), shows a still
  // (#t=0.3&play plays from there).
  setTime(hash.has("t") ? Number(hash.get("t")) : T[0]);
  setPlaying(hash.has("play") || (!hash.has("paused") && !hash.has("t") && !D.paused));
  renderer.render(scene, camera);
  if (hash.has("probe")) {  // #probe=BODY: a body's index; another value is reported, not thrown
    const b = Number(hash.get("probe"));
    if (Number.isInteger(b) && b >= 0 && b < D.bodies.length) { probe = b; reportProbe(probe); }
    else errors.push("#probe=" + hash.get("probe") + ": no body with that index (0.." + (D.bodies.length - 1) + ")");
  }
  if (hash.has("export")) {
    const what = hash.get("export");
    document.getElementById("export").textContent = what === "csv" ? plots.csvText() : plots.svgText(Number(what));
  }
  status.textContent = D.stop.complete ? "" : "run stopped at t = " + D.stop.t + " s: " + D.stop.message;
  // First contacts: named with their times in the bar (and marked on every plot).
  const contactMarks = D.marks.filter(function (m) { return m.kind === "contact"; });
  document.getElementById("contact").textContent = contactMarks.map(function (m) { return m.label + " at t = " + Number(m.t.toPrecision(6)) + " s"; }).join("; ");
  if (contactMarks.length) document.body.setAttribute("data-first-contact", String(contactMarks[0].t));
  flushErrors();
  document.body.setAttribute("data-ready", "1");
  document.body.setAttribute("data-ready-ms", performance.now().toFixed(0));  // since navigation start
  requestAnimationFrame(tick);
})();
