// urdf-lint's 3D page: the live preview (`urdf-lint preview`, the scene from state.json,
// reloaded when the server's version changes) and the review page of `urdf-lint diff --html`
// (window.URDF_LINT_REVIEW, written beside it: works from file://, meshes inlined as base64).
// Built on three.js and urdf-loader (static/vendor/vendor.js sets window.URDFV).
// window.preview is the page's state for the browser tests (tests/test_preview_browser.py).
(function () {
  'use strict';
  const V = window.URDFV;
  const REVIEW = window.URDF_LINT_REVIEW || null;
  const $ = (id) => document.getElementById(id);
  const el = (tag, attrs, ...kids) => {
    const e = document.createElement(tag);
    for (const [k, v] of Object.entries(attrs || {})) {
      if (k === 'text') e.textContent = v; else e.setAttribute(k, v);
    }
    kids.forEach((k) => e.appendChild(k));
    return e;
  };

  const state = {
    ready: false, version: -1, variant: 0, data: null, robots: [], markers: [],
    joints: {}, showVisual: true, showCollision: false, showFrames: false,
    highlight: new URLSearchParams(location.hash.slice(1)).get('highlight') || '',
    loadErrors: [], pending: 0, model: 0,
  };
  window.preview = state;

  // -- the 3D view ----------------------------------------------------------------------
  const view = $('view');
  const renderer = new V.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  view.appendChild(renderer.domElement);
  const scene = new V.Scene();
  scene.background = new V.Color(0xf4f5f7);
  const camera = new V.PerspectiveCamera(45, 1, 0.01, 1000);
  camera.up.set(0, 0, 1);
  camera.position.set(1.6, 1.2, 1.1);
  const controls = new V.OrbitControls(camera, renderer.domElement);
  state.camera = camera;
  scene.add(new V.HemisphereLight(0xffffff, 0x888888, 2.2));
  const sun = new V.DirectionalLight(0xffffff, 1.6);
  sun.position.set(3, 2, 5);
  scene.add(sun);
  const grid = new V.GridHelper(4, 40, 0xb0b4ba, 0xd4d7db);
  grid.rotation.x = Math.PI / 2;
  scene.add(grid);
  const world = new V.Group();          // the robots (URDF is z-up: so is the camera)
  scene.add(world);

  function resize() {
    const w = view.clientWidth || 800, h = view.clientHeight || 600;
    renderer.setSize(w, h, false);
    camera.aspect = w / h;
    camera.updateProjectionMatrix();
  }
  window.addEventListener('resize', resize);
  function frame() {
    controls.update();
    renderer.render(scene, camera);
    requestAnimationFrame(frame);
  }

  // -- meshes: served by the preview (m/<i>/<name>) or inlined by the review page ---------
  function b64ToBuffer(s) {
    const bin = atob(s), out = new Uint8Array(bin.length);
    for (let i = 0; i < bin.length; i++) out[i] = bin.charCodeAt(i);
    return out.buffer;
  }
  function meshLoader(manager, material, path, done) {
    let inline = REVIEW && REVIEW.files[path];
    if (inline && inline.same) inline = REVIEW.files[inline.same];   // (identical bytes)
    const fail = (err) => { state.loadErrors.push(path + ': ' + err); done(null, err); };
    const finish = (obj) => { done(obj); };
    const low = path.toLowerCase();
    if (path.startsWith('missing/') || (REVIEW && !inline)) {
      fail('not available'); return;
    }
    if (REVIEW && inline.refused) { fail(inline.refused); return; }
    try {
      if (low.endsWith('.stl')) {
        // (many STL files carry zero normals: drawn black without these)
        const mk = (g) => { g.computeVertexNormals();
                            return new V.Mesh(g, material || new V.MeshPhongMaterial()); };
        if (inline) finish(mk(new V.STLLoader(manager).parse(b64ToBuffer(inline.data))));
        else new V.STLLoader(manager).load(path, (g) => finish(mk(g)), null, fail);
      } else if (low.endsWith('.dae')) {
        const ld = new V.ColladaLoader(manager);
        if (inline) finish(ld.parse(atob(inline.data), '').scene);
        else ld.load(path, (d) => finish(d.scene), null, fail);
      } else if (low.endsWith('.obj')) {
        const ld = new V.OBJLoader(manager);
        const paint = (o) => {
          if (material) o.traverse((c) => { if (c.isMesh) c.material = material; });
          return o;
        };
        if (inline) finish(paint(ld.parse(atob(inline.data))));
        else ld.load(path, (o) => finish(paint(o)), null, fail);
      } else {
        fail('no loader for this format');
      }
    } catch (e) { fail(String(e)); }
  }

  // urdf-loader finds the root link with querySelector(`child[link="${name}"]`): a name with
  // a quote (a pull request writes any name) made that an invalid selector and the page blank.
  // The robot element answers that one query by comparing the attribute, not as CSS.
  function urdfDocument(urdf) {
    const doc = new DOMParser().parseFromString(urdf, 'text/xml');
    const robot = doc.documentElement;
    const asked = /^child\[link="([\s\S]*)"\]$/;
    robot.querySelector = (sel) => {
      const m = asked.exec(sel);
      if (!m) return Element.prototype.querySelector.call(robot, sel);
      return [...robot.getElementsByTagName('child')]
        .find((c) => c.getAttribute('link') === m[1]) || null;
    };
    return doc;
  }

  function loadRobot(urdf, opts) {
    // resolves once every mesh of the robot loaded or failed (own count: inlined meshes are
    // parsed without the LoadingManager ever hearing of them)
    return new Promise((resolve) => {
      const manager = new V.LoadingManager();
      const loader = new V.URDFLoader(manager);
      loader.parseCollision = true;
      loader.workingPath = '';
      let pending = 0, parsed = false, robot = null;
      const check = () => { if (parsed && pending === 0) resolve(robot); };
      loader.loadMeshCb = (path, mgr, material, done) => {
        pending += 1;
        meshLoader(mgr, material, path, (obj, err) => {
          done(obj, err);
          pending -= 1;
          check();
        });
      };
      robot = loader.parse(urdfDocument(urdf));
      robot.userData.side = opts.side || 'current';
      parsed = true;
      check();
    });
  }

  function styleRobot(robot, side, changed) {
    robot.traverse((c) => {
      if (c.isURDFCollider) c.userData.collider = true;
    });
    robot.traverse((c) => {
      if (!c.isMesh) return;
      let p = c.parent, collider = false, link = null;
      while (p) {
        if (p.userData && p.userData.collider) collider = true;
        if (!link && p.isURDFLink) link = p;
        p = p.parent;
      }
      c.userData.link = link ? link.name : '';
      c.userData.collision = collider;
      const mats = Array.isArray(c.material) ? c.material : [c.material];
      const out = mats.map((m) => {
        const n = m ? m.clone() : new V.MeshPhongMaterial();
        if (collider) {
          n.transparent = true; n.opacity = 0.35; n.color = new V.Color(0x7c3aed);
          n.depthWrite = false;
        }
        if (side === 'base') {
          n.transparent = true; n.opacity = 0.25; n.color = new V.Color(0x8a8f98);
          n.depthWrite = false;
        } else if (changed && changed.has(c.userData.link)) {
          n.emissive = new V.Color(CHANGED); n.emissiveIntensity = 0.8;
        }
        if (n.emissive) n.userData.base = [n.emissive.getHex(), n.emissiveIntensity];
        return n;
      });
      c.material = Array.isArray(c.material) ? out : out[0];
    });
  }

  // the highlighted element (state.highlight: "link:NAME", or "joint:NAME": its child link)
  // tinted blue; from the language server it follows the editor's cursor without a reload
  const HIGHLIGHT = 0x0077ff;
  function highlightedLink(robot) {
    const [kind, name] = state.highlight.split(/:(.*)/s);
    if (kind === 'link') return name;
    const j = kind === 'joint' && robot.joints[name];
    const child = j && j.children.find((c) => c.isURDFLink);
    return child ? child.name : null;
  }
  function applyHighlight() {
    state.robots.forEach((robot) => {
      if (robot.userData.side === 'base') return;
      const target = highlightedLink(robot);
      robot.traverse((c) => {
        if (!c.isMesh || c.userData.marker) return;
        (Array.isArray(c.material) ? c.material : [c.material]).forEach((m) => {
          if (!m || !m.emissive || !m.userData.base) return;
          const on = target !== null && c.userData.link === target;
          m.emissive.setHex(on ? HIGHLIGHT : m.userData.base[0]);
          m.emissiveIntensity = on ? 0.6 : m.userData.base[1];
        });
      });
    });
  }

  function applyVisibility() {
    state.robots.forEach((r) => r.traverse((c) => {
      if (c.isURDFCollider) c.visible = state.showCollision;
      else if (c.isURDFVisual) c.visible = state.showVisual;
      if (c.userData.frame) c.visible = state.showFrames;
    }));
  }

  function addFrames(robot) {
    const size = 0.08;
    Object.values(robot.links).forEach((link) => {
      const ax = new V.AxesHelper(size);
      ax.userData.frame = true;
      ax.visible = state.showFrames;
      link.add(ax);
    });
  }

  // -- findings as markers --------------------------------------------------------------
  function markerTarget(robot, target) {
    if (!target) return null;
    const [kind, name] = target;
    if (kind === 'link') return robot.links[name] || null;
    if (kind === 'joint') return robot.joints[name] || null;
    return null;
  }
  const CHANGED = 0xff1f8f;   // the review page's changed links (pink: robots are often orange)
  const SEV = { error: 0xd62828, warning: 0xf59e0b, info: 0x2563eb };
  function addMarkers(robot, findings) {
    state.markers = [];
    findings.forEach((f, i) => {
      const at = markerTarget(robot, f.target);
      if (!at) return;
      const m = new V.Mesh(new V.SphereGeometry(0.018, 16, 12),
                           new V.MeshBasicMaterial({ color: SEV[f.severity] || SEV.error,
                                                     depthTest: false }));
      m.renderOrder = 10;
      m.userData.finding = i;
      m.userData.marker = true;
      at.add(m);
      state.markers.push({ kind: f.target[0], name: f.target[1], code: f.code, index: i,
                           object: m });
    });
  }

  function showInfo(lines) {
    const info = $('info');
    info.textContent = '';
    lines.forEach((l) => info.appendChild(el('div', { text: l })));
  }
  function findingText(f) {
    return `${f.code}${f.name ? ' ' + f.name : ''}: ${f.message} (${f.file}${f.line ? ':' + f.line : ''})`;
  }

  const ray = new V.Raycaster();
  renderer.domElement.addEventListener('click', (ev) => {
    const r = renderer.domElement.getBoundingClientRect();
    const p = new V.Vector2(((ev.clientX - r.left) / r.width) * 2 - 1,
                            -((ev.clientY - r.top) / r.height) * 2 + 1);
    ray.setFromCamera(p, camera);
    const markers = state.markers.map((m) => m.object);
    const hitM = ray.intersectObjects(markers, false)[0];
    if (hitM) { pickFinding(hitM.object.userData.finding); return; }
    const hits = ray.intersectObjects(state.robots, true).filter((h) => h.object.visible);
    if (hits.length) pickLink(hits[0].object.userData.link);
  });

  function current() { return state.data ? state.data.variants[state.variant] : null; }

  // opened from the language server: a click also shows the element's xacro line in the
  // editor (POST jump: the server finds the line from the element's name; the page names no file)
  state.jumps = [];
  function jump(what) {
    if (REVIEW || !state.data || !state.data.editor) return;
    // (version: of the scenes, which a moved highlight does not change)
    const body = Object.assign({ version: state.data.scene_version, variant: state.variant },
                               what);
    fetch('jump', { method: 'POST', cache: 'no-store', body: JSON.stringify(body),
                    headers: { 'Content-Type': 'application/json' } })
      .then((r) => r.json().then((j) => state.jumps.push([r.status, j.result])))
      .catch((e) => state.jumps.push([0, String(e)]));
  }

  function pickFinding(i) {
    const f = current().findings[i];
    state.picked = { finding: i, target: f.target };
    showInfo([findingText(f)]);
    jump({ finding: i });
  }
  window.previewPickFinding = pickFinding;

  function pickLink(name) {
    const v = current();
    const at = v.links[name];
    const lines = [`link ${name}` + (at ? ` (${at[0]}:${at[1]})` : '')];
    v.findings.filter((f) => f.target && f.target[0] === 'link' && f.target[1] === name)
      .forEach((f) => lines.push(findingText(f)));
    state.picked = { link: name };
    showInfo(lines);
    jump({ element: 'link:' + name });
  }
  window.previewPickLink = pickLink;

  function pickJoint(name) {
    const at = current().joints[name];
    state.picked = { joint: name };
    showInfo([`joint ${name}` + (at ? ` (${at[0]}:${at[1]})` : '')]);
    jump({ element: 'joint:' + name });
  }

  // -- controls ---------------------------------------------------------------------------
  function movable(j) { return j.jointType !== 'fixed' && !j.mimicJoint; }
  function setJoint(name, value) {
    state.joints[name] = value;
    state.robots.forEach((r) => { if (r.joints[name]) r.setJointValue(name, value); });
    const s = document.querySelector(`input[data-joint="${CSS.escape(name)}"]`);
    if (s && Number(s.value) !== value) s.value = value;
  }
  state.setJoint = setJoint;

  function checkbox(label, key, after) {
    const c = el('input', { type: 'checkbox', id: 'toggle-' + key });
    c.checked = state[key];
    c.addEventListener('change', () => { state[key] = c.checked; after(); });
    return el('label', {}, c, document.createTextNode(' ' + label));
  }

  function buildControls(robot) {
    const box = $('controls');
    box.textContent = '';
    if (state.data.variants.length > 1) {
      const sel = el('select', { id: 'variant' });
      state.data.variants.forEach((v, i) => {
        const o = el('option', { value: String(i), text: v.label });
        if (i === state.variant) o.selected = true;
        sel.appendChild(o);
      });
      sel.addEventListener('change', () => { state.variant = Number(sel.value); show(); });
      box.appendChild(el('div', { class: 'row' }, el('span', { text: 'variant ' }), sel));
    }
    box.appendChild(el('div', { class: 'row' },
      checkbox('visual', 'showVisual', applyVisibility),
      checkbox('collision', 'showCollision', applyVisibility),
      checkbox('frames', 'showFrames', applyVisibility)));
    const joints = el('div', { id: 'joints' });
    Object.values(robot.joints).filter(movable).forEach((j) => {
      let lo = j.limit.lower, hi = j.limit.upper;
      if (j.jointType === 'continuous' || !(hi > lo)) { lo = -Math.PI; hi = Math.PI; }
      const v = state.joints[j.name] !== undefined ? state.joints[j.name] : Math.min(Math.max(0, lo), hi);
      const s = el('input', { type: 'range', min: String(lo), max: String(hi),
                              step: String((hi - lo) / 200), 'data-joint': j.name });
      s.value = v;
      s.addEventListener('input', () => setJoint(j.name, Number(s.value)));
      const label = el('span', { text: j.name, class: 'joint-name' });
      label.addEventListener('click', () => pickJoint(j.name));
      joints.appendChild(el('div', { class: 'joint' }, label, s));
      setJoint(j.name, v);
    });
    box.appendChild(joints);
  }

  function buildFindings(v) {
    const box = $('findings');
    box.textContent = '';
    const notes = (v.notes || []).concat(v.error ? [v.error] : []);
    notes.forEach((n) => box.appendChild(el('div', { class: 'note', text: n })));
    v.findings.forEach((f, i) => {
      const d = el('div', { class: 'finding ' + (f.severity || 'error'), text: findingText(f) });
      d.addEventListener('click', () => pickFinding(i));
      box.appendChild(d);
    });
  }

  function frameCamera(first) {
    const box = new V.Box3().setFromObject(world);
    if (box.isEmpty()) return;
    const c = box.getCenter(new V.Vector3());
    const r = Math.max(box.getSize(new V.Vector3()).length() / 2, 0.05);
    controls.target.copy(c);
    if (first) camera.position.set(c.x + r * 1.9, c.y + r * 1.5, c.z + r * 1.1);
    camera.near = r / 100; camera.far = r * 100;
    camera.updateProjectionMatrix();
  }

  async function show() {
    state.ready = false;
    const v = current();
    world.clear();
    state.robots = [];
    if (!v) {   // (from the language server, before the file's models are linted)
      $('title').textContent = 'urdf-lint: waiting for the lint of this file';
      state.ready = true;
      return;
    }
    $('title').textContent = v.label || 'urdf-lint';
    if (v.error || !v.urdf) {
      buildFindings(v);
      state.ready = true;
      return;
    }
    const first = state.framed !== state.variant;   // a new model: the camera frames it
    state.framed = state.variant;
    const changed = new Set(v.changed_links || []);
    if (v.base_urdf) {
      const base = await loadRobot(v.base_urdf, { side: 'base' });
      styleRobot(base, 'base', null);
      world.add(base);
      state.robots.push(base);
    }
    const robot = await loadRobot(v.urdf, { side: 'head' });
    styleRobot(robot, 'head', changed);
    addFrames(robot);
    addMarkers(robot, v.findings);
    world.add(robot);
    state.robots.push(robot);
    state.robot = robot;
    buildControls(robot);
    buildFindings(v);
    applyVisibility();
    applyHighlight();
    frameCamera(first);
    if (REVIEW) buildChanges(v);
    state.ready = true;
  }

  function buildChanges(v) {
    const box = $('info');
    box.textContent = '';
    const t = el('table', { id: 'changes' });
    t.appendChild(el('tr', {}, el('th', { text: 'element' }), el('th', { text: 'change' })));
    (v.changes || []).forEach((c) => t.appendChild(el('tr', {},
      el('td', { text: c.element }), el('td', { text: c.text }))));
    box.appendChild(el('div', { class: 'note',
      text: 'translucent grey: the base revision; pink: changed or moved links' }));
    box.appendChild(el('h2', { text: `${(v.changes || []).length} changes` }));
    box.appendChild(t);
    [['new findings', v.new_findings], ['fixed findings', v.fixed_findings]].forEach(([h, fs]) => {
      box.appendChild(el('h2', { text: `${(fs || []).length} ${h}` }));
      (fs || []).forEach((f) => box.appendChild(el('div', { class: 'finding', text: findingText(f) })));
    });
  }

  // -- data: the live server or the review page ------------------------------------------
  async function fetchState() {
    const r = await fetch('state.json', { cache: 'no-store' });
    return r.json();
  }
  async function follow() {
    for (;;) {
      try {
        const r = await fetch('version?v=' + state.version, { cache: 'no-store' });
        const { version } = await r.json();
        if (version !== state.version) {
          const before = state.data;
          state.data = await fetchState();
          state.version = state.data.version;
          state.variant = Math.max(0, Math.min(state.variant, state.data.variants.length - 1));
          if (state.data.editor) state.highlight = state.data.highlight || '';
          if (before && before.scene_version === state.data.scene_version) {
            applyHighlight();   // (the same scenes: only the highlight moved)
          } else {
            await show();
          }
        }
      } catch (e) {
        await new Promise((res) => setTimeout(res, 1000));
      }
    }
  }

  async function main() {
    resize();
    requestAnimationFrame(frame);
    if (REVIEW) {
      state.data = { variants: REVIEW.models, version: 0 };
      if (REVIEW.models.length > 1) {
        // one review page, every changed model: the picker is the variant picker
      }
      state.version = 0;
      await show();
      return;
    }
    state.data = await fetchState();
    state.version = state.data.version;
    if (state.data.editor) state.highlight = state.data.highlight || '';
    await show();
    follow();
  }
  main();
})();
