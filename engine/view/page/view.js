// pbfengine live view: the page's script. The protocol is the one of the engine's view server
// (server-sent events at /events, binary frames at /frame, solids at /solids, POST /control).
// Plain ES2017 with the non-module three.js r111 (global THREE), no build step.
'use strict';
(function () {
  const $ = (id) => document.getElementById(id);
  // Every data request carries the token in its query (EventSource cannot set headers).
  const token = new URLSearchParams(location.search).get('token') || '';
  // Relative URLs keep every request same-origin, which the server's Host/Origin checks demand.
  const dataUrl = (path) => path + '?token=' + encodeURIComponent(token);

  const MAX_POINTS = 20000;   // per thermo column, halved when exceeded
  const MAX_LOG = 2000;       // log lines kept
  const RETRY_MS = 2000;      // reconnect period once the event stream broke
  const SILENCE_MS = 60000;   // no event at all for this long while the run runs: reconnect

  const pbfView = window.pbfView = { frames: 0, rows: 0, lastFrame: null, pictures: [], webgl: false };

  // ---------------------------------------------------------------- formatting
  function fmt(v, digits) {
    if (v === null || v === undefined || !isFinite(v)) return '–';
    const a = Math.abs(v);
    if (a !== 0 && (a >= 1e6 || a < 1e-3)) return v.toExponential((digits || 4) - 1);
    return String(+v.toPrecision(digits || 4));
  }
  function hms(seconds) {
    if (seconds === null || seconds === undefined || !isFinite(seconds) || seconds < 0) return '–';
    const s = Math.round(seconds), h = Math.floor(s / 3600), m = Math.floor(s / 60) % 60;
    return h + ':' + String(m).padStart(2, '0') + ':' + String(s % 60).padStart(2, '0');
  }
  const unitText = (u) => (u && u !== '-' ? u : '');

  // ---------------------------------------------------------------- viridis
  // Matplotlib's viridis sampled at 9 points, interpolated into a 256-entry table once.
  const VIRIDIS = ['#440154', '#472d7b', '#3b528b', '#2c728e', '#21918c', '#28ae80', '#5ec962', '#addc30', '#fde725'];
  const LUT = new Float32Array(256 * 3);
  (function () {
    const rgb = VIRIDIS.map((h) => [1, 3, 5].map((i) => parseInt(h.substr(i, 2), 16) / 255));
    for (let i = 0; i < 256; i++) {
      const f = i / 255 * (rgb.length - 1), k = Math.min(Math.floor(f), rgb.length - 2), w = f - k;
      for (let c = 0; c < 3; c++) LUT[i * 3 + c] = rgb[k][c] * (1 - w) + rgb[k + 1][c] * w;
    }
  })();

  // ---------------------------------------------------------------- 3D view
  const V = { ok: false, cap: 0, spacing: 0, queued: false };   // renderer, scene, camera, controls, points…

  function requestRender() {
    if (!V.ok || V.queued) return;
    V.queued = true;
    requestAnimationFrame(() => { V.queued = false; V.renderer.render(V.scene, V.camera); });
  }

  function noWebGL(why) {
    const d = $('viewport').appendChild(document.createElement('div'));
    d.className = 'nogl';
    d.textContent = 'WebGL is unavailable here (' + why + '): the 3D view is off; everything else works.';
  }

  // A shaded disc so that the points read as small spheres rather than flat squares.
  function discTexture() {
    const c = document.createElement('canvas');
    c.width = c.height = 64;
    const g = c.getContext('2d'), grad = g.createRadialGradient(26, 24, 2, 32, 32, 31);
    grad.addColorStop(0, '#ffffff'); grad.addColorStop(0.6, '#d8d8d8'); grad.addColorStop(1, '#7a7a7a');
    g.fillStyle = grad; g.beginPath(); g.arc(32, 32, 31, 0, 2 * Math.PI); g.fill();
    return new THREE.CanvasTexture(c);
  }

  function init3d() {
    if (typeof THREE === 'undefined') { noWebGL('three.js did not load'); return; }
    V.camera = new THREE.PerspectiveCamera(45, 16 / 9, 0.01, 100);
    V.camera.up.set(0, 0, 1);   // z up; must be set before OrbitControls reads it
    let canvas = document.createElement('canvas'), gl = null;
    try { gl = canvas.getContext('webgl', { antialias: true }) || canvas.getContext('experimental-webgl'); } catch (e) { gl = null; }
    if (!gl) { noWebGL('no WebGL context'); return; }
    try {
      V.renderer = new THREE.WebGLRenderer({ canvas: canvas, context: gl, antialias: true });
    } catch (e) { noWebGL(e.message); return; }
    V.renderer.setPixelRatio(window.devicePixelRatio || 1);
    V.renderer.setClearColor(0x14171c);
    $('viewport').insertBefore(canvas, $('viewport').firstChild);
    V.scene = new THREE.Scene();
    V.scene.add(new THREE.AmbientLight(0xffffff, 0.6));
    const sun = new THREE.DirectionalLight(0xffffff, 0.55);
    sun.position.set(0.3, 0.5, 1);
    V.camera.add(sun);           // a head light keeps the solids lit from any side
    V.scene.add(V.camera);
    V.material = new THREE.PointsMaterial({ size: 0.01, sizeAttenuation: true, vertexColors: THREE.VertexColors,
                                            map: discTexture(), alphaTest: 0.5 });
    V.solids = new THREE.Group();
    V.scene.add(V.solids);
    if (THREE.OrbitControls) {
      V.controls = new THREE.OrbitControls(V.camera, canvas);
      V.controls.screenSpacePanning = true;
      V.controls.addEventListener('change', requestRender);
    }
    V.ok = pbfView.webgl = true;
    $('reset-view').hidden = false;
    new ResizeObserver(resize3d).observe($('viewport'));
    resize3d();
  }

  function resize3d() {
    if (!V.ok) return;
    const host = $('viewport'), w = Math.max(1, host.clientWidth), h = Math.max(1, host.clientHeight);
    V.renderer.setSize(w, h, false);
    V.camera.aspect = w / h;
    V.camera.updateProjectionMatrix();
    requestRender();
  }

  // Points have a world-space diameter: three's attenuation gives size*(height/2)/depth pixels,
  // the projection spacing*(height/2)/(depth*tan(fov/2)), hence the division by tan(fov/2).
  function updatePointSize() {
    if (V.ok && V.spacing > 0) V.material.size = 1.5 * V.spacing / Math.tan(V.camera.fov * Math.PI / 360);
  }

  function setDomain(domain, reframe) {
    if (!V.camera || !domain) return;
    const lo = new THREE.Vector3().fromArray(domain.lo), hi = new THREE.Vector3().fromArray(domain.hi);
    if (V.ok) {
      if (V.box) V.scene.remove(V.box);
      V.box = new THREE.Box3Helper(new THREE.Box3(lo, hi), 0x8a93a0);
      V.scene.add(V.box);
    }
    if (!reframe) return requestRender();
    // A 3/4 view from the front-right and above, as near as keeps every corner of the domain in sight.
    const center = lo.clone().add(hi).multiplyScalar(0.5), dir = new THREE.Vector3(0.9, -1.6, 0.9).normalize();
    const right = new THREE.Vector3().crossVectors(V.camera.up, dir).normalize();
    const up = new THREE.Vector3().crossVectors(dir, right);
    const tv = Math.tan(V.camera.fov * Math.PI / 360), th = tv * V.camera.aspect;
    let dist = 1e-6;
    for (let i = 0; i < 8; i++) {
      const v = new THREE.Vector3(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z).sub(center);
      dist = Math.max(dist, v.dot(dir) + Math.max(Math.abs(v.dot(up)) / tv, Math.abs(v.dot(right)) / th));
    }
    dist *= 1.12;
    V.camera.position.copy(center).addScaledVector(dir, dist);
    V.camera.near = dist / 1000; V.camera.far = dist * 50;
    V.camera.updateProjectionMatrix();
    V.target = center;   // where the camera looks when there are no controls (no WebGL)
    if (V.controls) { V.controls.target.copy(center); V.controls.update(); } else V.camera.lookAt(center);
    requestRender();
  }

  // Copies a frame into the points' attributes; they are reallocated only when the count outgrows them.
  function drawPoints(pos, val, n, lo, hi) {
    if (!V.ok) return;
    if (!V.points || n > V.cap || n < V.cap / 2) {
      const cap = V.points && n > V.cap ? Math.ceil(n * 1.25) : Math.max(n, 1);
      const g = new THREE.BufferGeometry();
      g.setAttribute('position', new THREE.BufferAttribute(new Float32Array(cap * 3), 3).setUsage(THREE.DynamicDrawUsage));
      g.setAttribute('color', new THREE.BufferAttribute(new Float32Array(cap * 3), 3).setUsage(THREE.DynamicDrawUsage));
      if (V.points) { V.points.geometry.dispose(); V.points.geometry = g; }
      else { V.points = new THREE.Points(g, V.material); V.points.frustumCulled = false; V.scene.add(V.points); }
      V.cap = cap;
    }
    const g = V.points.geometry, pa = g.attributes.position, ca = g.attributes.color;
    pa.array.set(pos);
    const col = ca.array, scale = hi > lo ? 255 / (hi - lo) : 0;
    for (let i = 0; i < n; i++) {
      const v = val[i];
      if (v !== v) { col[3 * i] = col[3 * i + 1] = col[3 * i + 2] = 0.5; continue; }   // NaN: grey
      const k = 3 * Math.max(0, Math.min(255, Math.round((v - lo) * scale)));
      col[3 * i] = LUT[k]; col[3 * i + 1] = LUT[k + 1]; col[3 * i + 2] = LUT[k + 2];
    }
    pa.updateRange.count = ca.updateRange.count = 3 * n;   // upload only what is used
    pa.needsUpdate = ca.needsUpdate = true;
    g.setDrawRange(0, n);
    requestRender();
  }

  function setSolids(list) {
    if (!V.ok) return;
    for (const o of V.solids.children.slice()) {
      V.solids.remove(o);
      o.geometry.dispose(); o.material.dispose();
    }
    for (const s of list) {
      const g = new THREE.BufferGeometry();
      g.setAttribute('position', new THREE.Float32BufferAttribute(s.vertices, 3));
      const nv = s.vertices.length / 3;
      g.setIndex(nv > 65535 ? new THREE.Uint32BufferAttribute(s.triangles, 1) : new THREE.Uint16BufferAttribute(s.triangles, 1));
      g.computeVertexNormals();
      const mat = (side, opacity) => new THREE.MeshLambertMaterial({ color: 0xa0a6ae, side: side, transparent: true,
                                                                     opacity: opacity, depthWrite: false });
      if (s.container) {
        // The inside (far walls) clearly, the near walls as a light veil over the fluid.
        V.solids.add(new THREE.Mesh(g, mat(THREE.BackSide, 0.3)));
        V.solids.add(new THREE.Mesh(g, mat(THREE.FrontSide, 0.07)));
      } else {
        V.solids.add(new THREE.Mesh(g, mat(THREE.DoubleSide, 0.45)));
      }
      V.solids.add(new THREE.LineSegments(new THREE.EdgesGeometry(g, 25),
                                          new THREE.LineBasicMaterial({ color: 0xb8bec6, transparent: true, opacity: 0.6 })));
    }
    requestRender();
  }

  function pictureCamera() {
    if (!V.camera) return null;
    const target = V.controls ? V.controls.target : V.target || new THREE.Vector3();
    const c = V.ok ? V.renderer.domElement : { width: 1280, height: 720 };
    return { camera: { position: V.camera.position.toArray(), target: target.toArray(), up: V.camera.up.toArray(),
                       fov: V.camera.fov }, width: c.width, height: c.height };
  }

  // ---------------------------------------------------------------- colour bar
  (function () {
    const c = $('colorbar-ramp'), g = c.getContext('2d');
    for (let x = 0; x < c.width; x++) {
      const k = 3 * Math.round(x / (c.width - 1) * 255);
      g.fillStyle = 'rgb(' + [0, 1, 2].map((i) => Math.round(LUT[k + i] * 255)).join(',') + ')';
      g.fillRect(x, 0, 1, c.height);
    }
  })();
  function setColorbar(field, unit, lo, hi) {
    $('colorbar-name').textContent = field + (unitText(unit) ? ' [' + unit + ']' : '');
    $('colorbar-min').textContent = fmt(lo);
    $('colorbar-max').textContent = fmt(hi);
    $('colorbar').hidden = false;
  }

  // ---------------------------------------------------------------- thermo plots
  // All columns share one x array; every plotted column has its ys and canvas.
  const T = { columns: [], xs: [], plots: [], lastStep: -Infinity, skipUpTo: -Infinity, queued: false };

  function resetPlots(columns) {
    T.columns = columns || [];
    T.xs = []; T.lastStep = -Infinity; T.skipUpTo = -Infinity;
    pbfView.rows = 0;   // the rows of this run
    const names = T.columns.map((c) => c.name);
    T.stepCol = names.indexOf('step');
    T.xCol = names.indexOf('time') >= 0 ? names.indexOf('time') : T.stepCol;
    T.xName = T.xCol >= 0 ? names[T.xCol] : 'step';
    T.xUnit = T.xCol >= 0 ? unitText(T.columns[T.xCol].unit) : '';
    const host = $('plots');
    host.textContent = '';
    T.plots = [];
    T.columns.forEach((col, i) => {
      if (col.name === 'step' || col.name === 'time') return;
      const box = document.createElement('div');
      box.className = 'plot';
      box.innerHTML = '<div class="plot-head"><span class="name"></span><span class="unit"></span>' +
                      '<span class="value">–</span></div><canvas></canvas>';
      box.querySelector('.name').textContent = col.name;
      box.querySelector('.unit').textContent = unitText(col.unit) ? '[' + col.unit + ']' : '';
      const canvas = box.querySelector('canvas');
      canvas.dataset.column = col.name;
      canvas.dataset.points = '0';
      host.appendChild(box);
      T.plots.push({ index: i, col: col, ys: [], canvas: canvas, value: box.querySelector('.value') });
    });
    if (!T.plots.length) host.innerHTML = '<div class="empty">' + (columns ? 'no thermo columns' : 'waiting for the run…') + '</div>';
  }

  function addRow(row) {
    const vals = (row.values || []).map((v) => (v === null || v === undefined ? NaN : +v));
    const step = T.stepCol >= 0 ? vals[T.stepCol] : +row.step;
    if (step <= T.skipUpTo) return;       // a replay after a reconnection: rows already plotted
    T.skipUpTo = -Infinity;
    T.lastStep = step;
    pbfView.rows++;
    T.xs.push(T.xCol >= 0 ? vals[T.xCol] : +row.step);
    for (const p of T.plots) p.ys.push(vals[p.index]);
    if (T.xs.length > MAX_POINTS) {
      // Halve every series alike, keeping the newest point.
      const keep = (a) => a.filter((_, i) => i % 2 === 0 || i === a.length - 1);
      T.xs = keep(T.xs);
      for (const p of T.plots) p.ys = keep(p.ys);
    }
    for (const p of T.plots) p.canvas.dataset.points = String(p.ys.length);   // in step with pbfView.rows
    schedulePlots();
  }

  // Plots and their labels follow the rows once per animation frame: a replay of thousands of
  // rows after a reconnection costs one redraw.
  function schedulePlots() {
    if (T.queued) return;
    T.queued = true;
    requestAnimationFrame(() => {
      T.queued = false;
      for (const p of T.plots) {
        p.value.textContent = fmt(p.ys[p.ys.length - 1], 5);
        drawPlot(p);
      }
    });
  }

  // Per pixel column the first, min, max and last value (M4): exact-looking at any point count.
  function drawPlot(p) {
    const c = p.canvas, dpr = window.devicePixelRatio || 1;
    const w = Math.max(40, c.clientWidth), h = Math.max(30, c.clientHeight);
    if (c.width !== Math.round(w * dpr) || c.height !== Math.round(h * dpr)) {
      c.width = Math.round(w * dpr); c.height = Math.round(h * dpr);
    }
    const g = c.getContext('2d');
    g.setTransform(dpr, 0, 0, dpr, 0, 0);
    g.clearRect(0, 0, w, h);
    const xs = T.xs, ys = p.ys;
    let x0 = Infinity, x1 = -Infinity, y0 = Infinity, y1 = -Infinity;
    for (let i = 0; i < ys.length; i++) {
      if (!isFinite(xs[i]) || !isFinite(ys[i])) continue;
      x0 = Math.min(x0, xs[i]); x1 = Math.max(x1, xs[i]); y0 = Math.min(y0, ys[i]); y1 = Math.max(y1, ys[i]);
    }
    g.font = '10px ui-monospace, monospace';
    g.fillStyle = '#8b94a0';
    if (y0 > y1) { g.fillText('no data yet', 6, h / 2); return; }
    if (y0 === y1) { const d = Math.abs(y0) * 0.05 || 1; y0 -= d; y1 += d; }
    if (x0 === x1) x1 = x0 + 1;
    const L = 4, R = 4, top = 13, bottom = 13, pw = w - L - R, ph = h - top - bottom;
    const sx = (pw - 1) / (x1 - x0), sy = ph / (y1 - y0), Y = (v) => top + (y1 - v) * sy;
    g.fillText(fmt(y1), L, 10);
    g.fillText(fmt(y0), L, h - 3);
    const xr = T.xName + ' ' + fmt(x0) + ' … ' + fmt(x1) + (T.xUnit ? ' ' + T.xUnit : '');
    g.fillText(xr, w - R - g.measureText(xr).width, h - 3);
    g.strokeStyle = '#2a3038';
    g.strokeRect(L + 0.5, top + 0.5, pw - 1, ph - 1);
    if (y0 < 0 && y1 > 0) { g.beginPath(); g.moveTo(L, Math.round(Y(0)) + 0.5); g.lineTo(L + pw, Math.round(Y(0)) + 0.5); g.stroke(); }
    g.strokeStyle = '#5fb3f0';
    g.lineWidth = 1.25;
    g.beginPath();
    let col = -1, first = 0, mn = 0, mx = 0, last = 0, pen = false;
    const flush = () => {
      if (col < 0) return;
      for (const v of [first, mn, mx, last]) { g[pen ? 'lineTo' : 'moveTo'](L + col + 0.5, Y(v)); pen = true; }
      col = -1;
    };
    for (let i = 0; i < ys.length; i++) {
      const x = xs[i], y = ys[i];
      if (!isFinite(x) || !isFinite(y)) { flush(); pen = false; continue; }   // a gap in the line
      const px = Math.floor((x - x0) * sx);
      if (px !== col) { flush(); col = px; first = mn = mx = last = y; }
      else { mn = Math.min(mn, y); mx = Math.max(mx, y); last = y; }
    }
    flush();
    g.stroke();
  }

  // ---------------------------------------------------------------- log
  const logEl = $('log');
  let logLines = [], logResync = false;

  function appendLog(lines) {
    if (logResync) {
      // After a reconnection the server sends its last lines again: skip those already shown.
      logResync = false;
      const k = logOverlap(logLines, lines);
      if (k === 0 && logLines.length) lines = ['… reconnected: lines written meanwhile may be missing'].concat(lines);
      lines = lines.slice(k);
    }
    if (!lines.length) return;
    const atBottom = logEl.scrollTop + logEl.clientHeight >= logEl.scrollHeight - 8;
    const frag = document.createDocumentFragment();
    for (const line of lines) {
      const d = document.createElement('div');
      d.textContent = line;
      const m = /^\[(warn|warning|error|fatal)\]/i.exec(line);
      if (m) d.className = m[1].toLowerCase().startsWith('warn') ? 'warn' : 'error';
      frag.appendChild(d);
    }
    logEl.appendChild(frag);
    logLines = logLines.concat(lines);
    const extra = logLines.length - MAX_LOG;
    if (extra > 0) {
      const before = logEl.scrollHeight;
      logLines = logLines.slice(extra);
      for (let i = 0; i < extra; i++) logEl.removeChild(logEl.firstChild);
      if (!atBottom) logEl.scrollTop -= before - logEl.scrollHeight;   // keep the reader's place
    }
    if (atBottom) logEl.scrollTop = logEl.scrollHeight;
  }

  // The largest k with the last k lines shown equal to the first k lines received.
  function logOverlap(have, got) {
    for (let k = Math.min(have.length, got.length); k > 0; k--) {
      let same = true;
      for (let i = 0; i < k && same; i++) same = have[have.length - k + i] === got[i];
      if (same) return k;
    }
    return 0;
  }

  function clearLog() { logLines = []; logEl.textContent = ''; logResync = false; }

  // ---------------------------------------------------------------- banner and notices
  let bannerTimer = null, noticeTimer = null;
  function banner(text, kind, ms) {
    const b = $('banner');
    clearTimeout(bannerTimer);
    [b.textContent, b.className, b.hidden] = [text || '', kind || '', !text];
    if (text && ms) bannerTimer = setTimeout(() => banner(connected ? '' : LOST, connected ? '' : 'lost'), ms);
  }
  function notice(text, isError) {
    clearTimeout(noticeTimer);
    [$('notice').textContent, $('notice').className] = [text, isError ? 'error' : ''];
    noticeTimer = setTimeout(() => { $('notice').textContent = ''; }, isError ? 15000 : 10000);
  }

  // ---------------------------------------------------------------- run state
  let hello = null, state = '', pendingColor = null;

  // running and paused are live; finished, stopped, failed (or anything else) end the run.
  function setState(s, message) {
    if (message && s !== state) notice(s + ': ' + message, s === 'failed');
    state = s || state;
    $('state').textContent = state || '–';
    $('state').dataset.state = state;
    $('state').title = message || '';
    const over = state !== '' && state !== 'running' && state !== 'paused';
    for (const id of ['pause', 'resume', 'step-once', 'stop']) $(id).disabled = over;
  }

  function onHello(h, firstOnConnection) {
    // A new run: another run_id, or a second hello on the same connection.
    const newRun = hello !== null && (h.run_id !== hello.run_id || !firstOnConnection);
    const domainChanged = !hello || JSON.stringify(hello.domain) !== JSON.stringify(h.domain);
    if (hello === null || newRun) {
      resetPlots(h.columns);
      if (h.run_id !== (hello && hello.run_id)) clearLog(); else logResync = true;
      solidsVersion = null;
      F.meta.clear();   // frame numbers may start again
      if (hello !== null) banner('new run: ' + (h.title || h.run_id), 'info', 6000);
    } else {
      // The same run after a reconnection: the replayed rows and lines are already shown.
      T.skipUpTo = T.lastStep;
      logResync = true;
    }
    hello = h;
    document.title = (h.title || 'run') + ' · pbfengine';
    $('title').textContent = h.title || 'pbfengine';
    $('color').textContent = '';
    for (const f of h.fields || []) $('color').add(new Option(f, f));
    if (h.color) $('color').value = h.color;
    V.spacing = +h.spacing || 0;
    updatePointSize();
    setDomain(h.domain, domainChanged);
    setState(h.state);
    if (!pbfView.lastFrame) $('particles').textContent = '–';
  }

  function onStatus(s) {
    $('step').textContent = String(s.step);
    $('time').textContent = fmt(s.time, 5) + ' s';
    $('sps').textContent = s.steps_per_second == null ? '–' : (+s.steps_per_second).toFixed(1);
    $('left').textContent = hms(s.seconds_left);
    setState(s.state, s.message);
    // Progress along the plan: by steps when the last step is known, else by time.
    const plan = (hello && hello.plan) || {}, s0 = plan.first_step || 0;
    const f = plan.last_step > s0 ? (s.step - s0) / (plan.last_step - s0) : plan.end_time ? s.time / plan.end_time : NaN;
    const bar = $('progress'), pct = 100 * Math.max(0, Math.min(1, f));
    bar.hidden = !isFinite(f);
    bar.firstElementChild.style.width = pct.toFixed(2) + '%';
    bar.title = Math.round(pct) + '% of the planned run';
  }

  // ---------------------------------------------------------------- frames and solids
  // At most one /frame request at a time; events arriving meanwhile fold into one more fetch.
  const F = { busy: false, newer: false, meta: new Map(), latest: null };
  let solidsVersion = null, solidsBusy = false;

  function onFrame(ev) {
    F.latest = ev;
    F.meta.set(ev.seq, ev);
    if (F.meta.size > 16) F.meta.delete(F.meta.keys().next().value);
    if (ev.color && pendingColor === null && document.activeElement !== $('color')) $('color').value = ev.color;
    if (pendingColor !== null && ev.color === pendingColor) pendingColor = null;
    if (ev.solids_version !== undefined && ev.solids_version !== solidsVersion) fetchSolids(ev.solids_version);
    if (F.busy) { F.newer = true; return; }
    fetchFrame();
  }

  async function fetchFrame() {
    F.busy = true;
    F.newer = false;
    // A request that never ends (a half-open connection) must not stop the frames for good.
    const abort = new AbortController(), timer = setTimeout(() => abort.abort(), 20000);
    try {
      const r = await fetch(dataUrl('frame'), { cache: 'no-store', signal: abort.signal });
      if (!r.ok) throw new Error('HTTP ' + r.status);
      drawFrame(await r.arrayBuffer());
      // Take the next frame once this one is on screen; a hidden tab (no animation frames) takes one
      // a second, so that it costs the engine little yet never holds up another page's frames.
      await new Promise((resolve) => { requestAnimationFrame(resolve); setTimeout(resolve, 1000); });
    } catch (e) {
      console.warn('frame:', e.message);
    } finally {
      clearTimeout(timer);
      F.busy = false;
      if (F.newer) fetchFrame();
    }
  }

  function drawFrame(buf) {
    const dv = new DataView(buf);
    if (buf.byteLength < 32 || String.fromCharCode(dv.getUint8(0), dv.getUint8(1), dv.getUint8(2), dv.getUint8(3)) !== 'PBFV')
      throw new Error('not a PBFV frame');
    const n = dv.getUint32(4, true), time = dv.getFloat64(8, true);
    const step = dv.getInt32(20, true) * 4294967296 + dv.getUint32(16, true);
    const seq = dv.getUint32(24, true);
    if (buf.byteLength < 32 + 16 * n) throw new Error('short frame: ' + buf.byteLength + ' bytes for ' + n + ' particles');
    const pos = new Float32Array(buf, 32, 3 * n), val = new Float32Array(buf, 32 + 12 * n, n);
    // The colour range comes with the frame's event; without it, the values' own range.
    const meta = F.meta.get(seq) || F.latest || {};
    let lo = meta.min, hi = meta.max;
    if (meta.seq !== seq || !isFinite(lo) || !isFinite(hi)) {
      lo = Infinity; hi = -Infinity;
      for (let i = 0; i < n; i++) if (val[i] === val[i]) { lo = Math.min(lo, val[i]); hi = Math.max(hi, val[i]); }
      if (lo > hi) lo = hi = 0;
    }
    drawPoints(pos, val, n, lo, hi);
    setColorbar(meta.color || $('color').value, meta.unit, lo, hi);
    pbfView.frames++;
    pbfView.lastFrame = { seq: seq, step: step, count: n };
    $('particles').textContent = String(n);
    $('frame-info').textContent = 'frame ' + seq + ' · step ' + step + ' · t = ' + fmt(time, 5) + ' s';
  }

  async function fetchSolids(version) {
    if (solidsBusy) return;
    solidsBusy = true;
    try {
      const r = await fetch(dataUrl('solids'), { cache: 'no-store' });
      if (!r.ok) throw new Error('HTTP ' + r.status);
      const j = await r.json();
      setSolids(j.solids || []);
      solidsVersion = j.version !== undefined ? j.version : version;
    } catch (e) { console.warn('solids:', e.message); }   // tried again on the next frame event
    solidsBusy = false;
  }

  // ---------------------------------------------------------------- controls
  async function control(body) {
    try {
      const r = await fetch(dataUrl('control'), { method: 'POST', headers: { 'Content-Type': 'application/json' },
                                                 body: JSON.stringify(body) });
      let j = {};
      try { j = await r.json(); } catch (e) { /* a non-JSON answer: the status says enough */ }
      if (!r.ok || j.error) throw new Error(j.error || 'HTTP ' + r.status);
      return true;
    } catch (e) {
      notice(body.command + ': ' + e.message, true);
      return false;
    }
  }

  for (const [id, command] of [['pause', 'pause'], ['resume', 'resume'], ['step-once', 'step']])
    $(id).onclick = () => control({ command: command });
  $('stop').onclick = () => {
    if (window.confirm('Stop the run after this step and write a restart?')) control({ command: 'stop' });
  };
  $('picture').onclick = () => {
    const cam = pictureCamera();
    if (!cam) return notice('picture: no camera yet (no domain received)', true);
    control(Object.assign({ command: 'picture' }, cam)).then((ok) => ok && notice('picture requested…'));
  };
  $('color').onchange = () => {
    const field = $('color').value;
    pendingColor = field;
    setTimeout(() => { if (pendingColor === field) pendingColor = null; }, 5000);
    control({ command: 'color', field: field }).then((ok) => {   // refused: show the field in use again
      if (!ok && pendingColor === field) { pendingColor = null; if (F.latest) $('color').value = F.latest.color; }
    });
  };
  $('reset-view').onclick = () => hello && setDomain(hello.domain, true);

  function onPicture(p) {
    if (p.error) return notice('picture failed: ' + p.error, true);
    pbfView.pictures.push(p.path);
    notice('picture written: ' + p.path + (p.step !== undefined ? ' (step ' + p.step + ')' : ''));
  }

  // ---------------------------------------------------------------- connection
  const LOST = 'connection lost, reconnecting…';
  let es = null, connected = false, retryTimer = null, lastEventAt = 0, sawHello = false;

  function setConnected(on) {
    connected = on;
    $('connection').textContent = on ? 'connected' : 'disconnected';
    $('connection').className = on ? 'on' : 'off';
    if (!on) banner(LOST, 'lost');
    else if ($('banner').className === 'lost') banner('');
  }

  // On any error the stream is closed and opened anew every RETRY_MS: EventSource gives up by
  // itself after an HTTP error (the engine restarting, a proxy's 502), and this covers both.
  function connect() {
    clearTimeout(retryTimer);
    if (es) es.close();
    sawHello = false;
    es = new EventSource(dataUrl('events'));
    lastEventAt = Date.now();
    es.onopen = () => { lastEventAt = Date.now(); setConnected(true); };
    es.onerror = () => {
      if (es) es.close();
      es = null;
      F.newer = false;  // that frame was the lost stream's: a restarted engine has not made it
      setConnected(false);
      retryTimer = setTimeout(connect, RETRY_MS);
      // EventSource hides the HTTP status; a refused token (another user's run on this port) is told apart.
      fetch(dataUrl('solids'), { cache: 'no-store' }).then((r) => {
        if (r.status === 403 && !connected)
          banner('the engine refuses this page (403): open the address it printed', 'lost');
      }, () => {});
    };
    const on = (name, fn) => es.addEventListener(name, (e) => {
      lastEventAt = Date.now();
      let data;
      try { data = JSON.parse(e.data); } catch (err) { return console.warn(name + ': bad JSON', err); }
      fn(data);
    });
    on('hello', (h) => { onHello(h, !sawHello); sawHello = true; });
    on('thermo', addRow);
    on('log', (l) => appendLog(l.lines || []));
    on('status', onStatus);
    on('frame', onFrame);
    on('picture', onPicture);
  }

  // Keep-alive comments are invisible to scripts, so a silent stream is judged by the status
  // events a running run sends twice a second.
  setInterval(() => {
    if (es && connected && state === 'running' && Date.now() - lastEventAt > SILENCE_MS) es.onerror();
  }, 5000);

  // ---------------------------------------------------------------- start
  new ResizeObserver(schedulePlots).observe($('plots'));
  try { init3d(); } catch (e) { console.warn('3D view:', e); noWebGL(e.message); V.ok = pbfView.webgl = false; }
  resetPlots(null);
  setConnected(false);
  banner('');
  if (!token) banner('no token in the page address: open the URL the engine printed (…/?token=…)', 'lost');
  else connect();
})();
