// The page of `vantage view`: draws the data `vantage view` wrote into #vantage-data with three.js
// (inlined as #three-src). World frame: z up, metres.

// Colours. The headless test reads them back from the legend's data attributes and looks for
// them in a screenshot, so the cells and the chosen view are drawn unlit in exactly these.
const kHeightRamp = ['#440154', '#482878', '#3e4989', '#31688e', '#26828e', '#1f9e89', '#35b779',
                     '#6ece58', '#b5de2b', '#fde725'];  // viridis
const kGainRamp = ['#9ca3af', '#f97316', '#ef4444'];  // grey (least) -> orange -> red (most)
const kChosen = '#ff00ff';
const kTaken = '#ffffff';
const kUnobserved = '#9aa0aa';
const kBackground = '#1e2128';
// Brightness of a cube's faces (+x, -x, +y, -y, +z, -z), so cubes read as solids without lights.
const kFaceShade = [0.8, 0.8, 0.65, 0.65, 1.0, 0.5];

const $ = (id) => document.getElementById(id);

/// Imports three.js and OrbitControls from the text inlined in the page, as blob: modules (a
/// page opened from disk can fetch nothing; OrbitControls' `from 'three'` is pointed at the blob).
async function loadThree() {
  const blob = (text) => URL.createObjectURL(new Blob([text], {type: 'text/javascript'}));
  const threeUrl = blob($('three-src').textContent);
  const orbitText = $('orbit-src').textContent.replace(/from\s+'three'/, `from '${threeUrl}'`);
  const THREE = await import(threeUrl);
  const {OrbitControls} = await import(blob(orbitText));
  return {THREE, OrbitControls};
}

/// The ramp's colour at t in [0, 1], interpolated in sRGB (as the test and the CSS legend do).
function rampColor(THREE, ramp, t) {
  const x = Math.min(Math.max(t, 0), 1) * (ramp.length - 1);
  const i = Math.min(Math.floor(x), ramp.length - 2);
  const rgb = (hex, k) => parseInt(hex.slice(1 + 2 * k, 3 + 2 * k), 16) / 255;
  const mix = (k) => rgb(ramp[i], k) + (rgb(ramp[i + 1], k) - rgb(ramp[i], k)) * (x - i);
  return new THREE.Color().setRGB(mix(0), mix(1), mix(2), THREE.SRGBColorSpace);
}

function gradient(ramp) { return `linear-gradient(to right, ${ramp.join(', ')})`; }

function format(x, unit) {
  const digits = Math.abs(x) >= 100 ? 0 : Math.abs(x) >= 10 ? 1 : 2;
  return `${x.toFixed(digits)}${unit ? ' ' + unit : ''}`;
}

/// An InstancedMesh of cubes at the given cell indices (flat x, y, z triples).
function cellMesh(THREE, data, cells, material, colorOf) {
  const n = cells.length / 3;
  const r = data.grid.resolution;
  const o = data.grid.origin;
  const geometry = new THREE.BoxGeometry(r * 0.96, r * 0.96, r * 0.96);
  const shade = [];
  for (let face = 0; face < 6; ++face) {
    for (let v = 0; v < 4; ++v) shade.push(kFaceShade[face], kFaceShade[face], kFaceShade[face]);
  }
  geometry.setAttribute('color', new THREE.Float32BufferAttribute(shade, 3));
  const mesh = new THREE.InstancedMesh(geometry, material, n);
  const m = mesh.instanceMatrix.array;
  for (let i = 0; i < n; ++i) {
    m.set([1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0], 16 * i);
    m[16 * i + 12] = o[0] + (cells[3 * i] + 0.5) * r;
    m[16 * i + 13] = o[1] + (cells[3 * i + 1] + 0.5) * r;
    m[16 * i + 14] = o[2] + (cells[3 * i + 2] + 0.5) * r;
    m[16 * i + 15] = 1;
    if (colorOf) mesh.setColorAt(i, colorOf(cells[3 * i + 2]));
  }
  mesh.instanceMatrix.needsUpdate = true;
  mesh.computeBoundingSphere();
  return mesh;
}

/// The frustum's corners at depth `depth` in the world, after its apex.
function frustumCorners(THREE, sensor, pose, depth) {
  const q = new THREE.Quaternion(...pose.quaternion);
  const p = new THREE.Vector3(...pose.position);
  const y = depth * Math.tan(sensor.h_fov / 2);
  const z = depth * Math.tan(sensor.v_fov / 2);
  const corners = [[depth, y, z], [depth, -y, z], [depth, -y, -z], [depth, y, -z]];
  return [p, ...corners.map((c) => new THREE.Vector3(...c).applyQuaternion(q).add(p))];
}

/// Line segments of a frustum (apex to corners, and the far rectangle), appended to `out`.
function frustumLines(THREE, sensor, pose, depth, out) {
  const [apex, ...c] = frustumCorners(THREE, sensor, pose, depth);
  for (let i = 0; i < 4; ++i) out.push(apex, c[i], c[i], c[(i + 1) % 4]);
}

function linesOf(THREE, points, colors) {
  const geometry = new THREE.BufferGeometry().setFromPoints(points);
  geometry.setAttribute('color', new THREE.Float32BufferAttribute(colors.flatMap((c) => [c.r, c.g, c.b]), 3));
  return new THREE.LineSegments(geometry, new THREE.LineBasicMaterial({vertexColors: true}));
}

function label(THREE, text, position, size) {
  const canvas = document.createElement('canvas');
  canvas.width = canvas.height = 64;
  const g = canvas.getContext('2d');
  g.fillStyle = 'rgba(20, 22, 28, 0.8)';
  g.beginPath();
  g.arc(32, 32, 30, 0, 2 * Math.PI);
  g.fill();
  g.fillStyle = kTaken;
  g.font = 'bold 36px sans-serif';
  g.textAlign = 'center';
  g.textBaseline = 'middle';
  g.fillText(text, 32, 34);
  const texture = new THREE.CanvasTexture(canvas);
  texture.colorSpace = THREE.SRGBColorSpace;
  const sprite = new THREE.Sprite(new THREE.SpriteMaterial({map: texture, depthTest: false}));
  sprite.position.copy(position);
  sprite.scale.set(size, size, 1);
  sprite.renderOrder = 2;
  return sprite;
}

async function main() {
  const data = JSON.parse($('vantage-data').textContent);
  const {THREE, OrbitControls} = await loadThree();
  const sensor = data.sensor ?? {h_fov: 57 * Math.PI / 180, v_fov: 43 * Math.PI / 180,
                                 min_range: 0.5, max_range: 3.5};
  const grid = data.grid;
  const extent = grid.dims.map((d) => d * grid.resolution);
  const center = new THREE.Vector3(...grid.origin.map((o, i) => o + extent[i] / 2));
  // NOTE: the sensor reaches metres past a table top; frusta drawn that long would hide it.
  const depth = Math.min(sensor.max_range, 0.8, Math.max(0.1, 0.3 * Math.max(...extent)));

  $('heading').textContent = data.title;
  $('chosen-swatch').style.background = kChosen;
  $('taken-swatch').style.background = kTaken;
  $('taken-swatch').style.height = '2px';
  $('taken-swatch').style.verticalAlign = '3px';
  $('chosen-swatch').dataset.color = kChosen;
  $('height-bar').style.background = gradient(kHeightRamp);
  $('height-bar').dataset.ramp = kHeightRamp.join(',');
  $('gain-bar').style.background = gradient(kGainRamp);
  $('gain-bar').dataset.ramp = kGainRamp.join(',');
  const notes = [...data.notes];
  notes.push(`frusta are drawn ${format(depth, 'm')} deep; the sensor sees ` +
             `${format(sensor.min_range, 'm')} to ${format(sensor.max_range, 'm')}`);

  const renderer = new THREE.WebGLRenderer({canvas: $('canvas'), antialias: true});
  renderer.setPixelRatio(window.devicePixelRatio);
  renderer.setSize(window.innerWidth, window.innerHeight);
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(kBackground);
  const camera = new THREE.PerspectiveCamera(45, window.innerWidth / window.innerHeight,
                                             0.01, 1000);
  camera.up.set(0, 0, 1);

  const floor = new THREE.GridHelper(Math.max(extent[0], extent[1]) * 1.5, 12, 0x555a66, 0x3a3f4a);
  floor.rotation.x = Math.PI / 2;
  floor.position.set(center.x, center.y, grid.origin[2]);
  scene.add(floor);

  // Occupied cells, coloured by height; unobserved cells behind a toggle.
  const occupied = data.occupied;
  let zMin = Infinity, zMax = -Infinity;
  for (let i = 2; i < occupied.cells.length; i += 3) {
    zMin = Math.min(zMin, occupied.cells[i]);
    zMax = Math.max(zMax, occupied.cells[i]);
  }
  const height = (k) => grid.origin[2] + (k + 0.5) * grid.resolution;
  if (occupied.cells.length > 0) {
    const colorOf = (k) => rampColor(THREE, kHeightRamp, zMax > zMin ? (k - zMin) / (zMax - zMin) : 0.5);
    scene.add(cellMesh(THREE, data, occupied.cells,
                       new THREE.MeshBasicMaterial({vertexColors: true}), colorOf));
    $('height-min').textContent = format(height(zMin), 'm');
    $('height-max').textContent = format(height(zMax), 'm');
  } else {
    notes.push('the map has no occupied cells');
  }
  const drawnOccupied = occupied.cells.length / 3;
  if (drawnOccupied < occupied.total) {
    notes.push(`showing ${drawnOccupied} of ${occupied.total} occupied cells, evenly thinned ` +
               `(the cap is ${data.max_cells}; vantage view --max-cells)`);
  }
  const unobserved = data.unobserved;
  const drawnUnobserved = unobserved.cells.length / 3;
  let unobservedMesh = null;
  if (drawnUnobserved > 0) {
    unobservedMesh = cellMesh(THREE, data, unobserved.cells, new THREE.MeshBasicMaterial({
      color: kUnobserved, vertexColors: true, transparent: true, opacity: 0.18, depthWrite: false}));
    unobservedMesh.visible = $('show-unobserved').checked;
    scene.add(unobservedMesh);
  }
  $('unobserved-count').textContent =
      `(${drawnUnobserved < unobserved.total ? `${drawnUnobserved} of ` : ''}${unobserved.total} ` +
      `next to observed space; ${unobserved.all} in all)`;

  // Views taken: frusta, the order of scans and the path between them.
  const taken = new THREE.Group();
  scene.add(taken);
  const takenParts = data.scans.map((s, i) => {
    const part = new THREE.Group();
    const points = [];
    frustumLines(THREE, sensor, s, depth, points);
    part.add(linesOf(THREE, points, points.map(() => new THREE.Color(kTaken))));
    const apex = new THREE.Vector3(...s.position);
    part.add(label(THREE, String(s.scan), apex.clone().add(new THREE.Vector3(0, 0, depth * 0.3)),
                   Math.max(depth * 0.25, 0.03 * Math.max(...extent))));
    let path = s.path.map(([x, y]) => new THREE.Vector3(x, y, grid.origin[2] + 0.02));
    if (path.length === 0 && i > 0) path = [new THREE.Vector3(...data.scans[i - 1].position), apex];
    if (path.length > 1) {
      const segments = path.slice(1).flatMap((p, j) => [path[j], p]);
      part.add(linesOf(THREE, segments, segments.map(() => new THREE.Color(kTaken))));
    }
    taken.add(part);
    return part;
  });

  // Candidates of the decision shown, coloured by predicted gain; the chosen one solid.
  const candidates = new THREE.Group();
  scene.add(candidates);
  const units = data.units;
  function showDecision(decision) {
    candidates.clear();
    $('gain-legend').style.display = decision ? '' : 'none';
    if (!decision || decision.candidates.length === 0) return;
    const gains = decision.candidates.map((c) => c.gain);
    const lo = Math.min(...gains), hi = Math.max(...gains);
    const points = [], colors = [];
    decision.candidates.forEach((c, j) => {
      if (j === decision.chosen) return;
      const color = rampColor(THREE, kGainRamp, hi > lo ? (c.gain - lo) / (hi - lo) : 1);
      const before = points.length;
      frustumLines(THREE, sensor, c, depth, points);
      for (let k = before; k < points.length; ++k) colors.push(color);
    });
    if (points.length > 0) candidates.add(linesOf(THREE, points, colors));
    const chosen = decision.candidates[decision.chosen];
    const [apex, ...c] = frustumCorners(THREE, sensor, chosen, depth);
    const sides = [];
    for (let i = 0; i < 4; ++i) sides.push(apex, c[i], c[(i + 1) % 4]);
    const solid = new THREE.BufferGeometry().setFromPoints(sides);
    candidates.add(new THREE.Mesh(solid, new THREE.MeshBasicMaterial({
      color: kChosen, side: THREE.DoubleSide})));
    $('gain-title').textContent =
        `predicted gain of each candidate [${units.gain}], ${decision.candidates.length} candidates`;
    $('gain-min').textContent = format(lo, units.gain);
    $('gain-max').textContent = format(hi, units.gain);
  }

  // The slider: after scan k, the views taken so far and the decision that chose scan k + 1.
  const steps = data.source === 'plan' ? 1 : Math.max(data.scans.length, 1);
  const slider = $('slider');
  slider.max = String(steps);
  const decisionAfter = (k) => data.decisions.find((d) => d.after_scan === k);
  let step = data.source === 'plan' ? 1 : Math.max(1, steps - 1);
  if (data.source === 'explore' && !decisionAfter(step)) step = steps;
  slider.value = String(step);
  if (data.source === 'plan') $('step-row').style.display = 'none';

  function update() {
    const k = Number(slider.value);
    takenParts.forEach((part, i) => { part.visible = i < k; });
    const decision = data.source === 'plan' ? data.decisions[0] : decisionAfter(k);
    showDecision(decision);
    if (data.source === 'explore') {
      const s = data.scans[k - 1];
      $('step').textContent = s ? `after scan ${k} of ${data.scans.length}: ${s.unobserved} ` +
          `unobserved cells, coverage ${(100 * s.coverage).toFixed(1)} %` : '';
    }
    let text = '';
    if (decision) {
      const chosen = decision.candidates[decision.chosen];
      text = `${data.source === 'plan' ? 'next best view' : `decision for scan ${k + 1}`}: ` +
             `view ${chosen.view}, predicted ${format(chosen.gain, units.gain)} ` +
             `(greedy ${format(chosen.greedy, units.greedy)})`;
      const next = data.scans[k];
      if (data.source === 'explore' && next) text += `; the scan then saw ${next.actual_gain} cells`;
    } else if (data.source === 'explore') {
      text = k < data.scans.length ? 'no gains recorded for this decision' : 'the last scan';
    }
    $('decision').textContent = text;
    render();
  }

  // Camera: the whole grid and every view, from above and to one side.
  const box = new THREE.Box3().setFromCenterAndSize(center, new THREE.Vector3(...extent));
  for (const s of data.scans) box.expandByPoint(new THREE.Vector3(...s.position));
  for (const d of data.decisions) {
    for (const c of d.candidates) box.expandByPoint(new THREE.Vector3(...c.position));
  }
  const sphere = box.getBoundingSphere(new THREE.Sphere());
  const distance = sphere.radius / Math.sin((camera.fov * Math.PI) / 360) * 0.8;
  const azimuth = -Math.PI / 3, elevation = Math.PI / 5;
  camera.position.copy(sphere.center).add(new THREE.Vector3(
      Math.cos(azimuth) * Math.cos(elevation), Math.sin(azimuth) * Math.cos(elevation),
      Math.sin(elevation)).multiplyScalar(distance));
  camera.near = distance / 1000;
  camera.far = distance * 10;
  camera.updateProjectionMatrix();
  const controls = new OrbitControls(camera, renderer.domElement);
  controls.target.copy(sphere.center);
  controls.update();

  function render() { renderer.render(scene, camera); }
  // The panel covers the left of the window: centre the view in the rest of it.
  function fit() {
    const w = window.innerWidth, h = window.innerHeight;
    const shift = Math.min($('panel').offsetWidth + 10, w / 2) / 2;
    camera.aspect = w / h;
    camera.setViewOffset(w, h, -shift, 0, w, h);
    camera.updateProjectionMatrix();
    renderer.setSize(w, h);
  }
  fit();
  controls.addEventListener('change', render);
  window.addEventListener('resize', () => { fit(); render(); });
  slider.addEventListener('input', update);
  $('show-candidates').addEventListener('change', (e) => { candidates.visible = e.target.checked; render(); });
  $('show-taken').addEventListener('change', (e) => { taken.visible = e.target.checked; render(); });
  $('show-unobserved').addEventListener('change', (e) => {
    if (unobservedMesh) unobservedMesh.visible = e.target.checked;
    render();
  });

  $('summary').textContent = `${occupied.total} occupied cells of ${grid.resolution} m; ` +
      `${data.scans.length} scans; three.js ${data.three_version}`;
  $('notes').replaceChildren(...notes.map((n) => {
    const div = document.createElement('div');
    div.textContent = n;
    return div;
  }));
  update();
  if (window.vantageErrors.length === 0) {
    $('status').dataset.state = 'ready';
    $('status').textContent = 'ready';
  }
}

main().catch((e) => vantageFail(e && e.stack ? e.stack : e));
