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

/// A number as the terminal prints it: `digits` decimals and its unit ('-' when not recorded).
function fixed(x, digits, unit) {
  return x === null || x === undefined ? '-' : `${x.toFixed(digits)} ${unit}`;
}

/// An InstancedMesh of cubes at the given cell indices (flat x, y, z triples).
function cellMesh(THREE, data, cells, material, colorOf) {
  const n = cells.length / 3;
  // Lowest first, so that a height cut is the mesh's count (userData.countUpTo).
  const order = Array.from({length: n}, (_, i) => i).sort((a, b) => cells[3 * a + 2] - cells[3 * b + 2]);
  cells = order.flatMap((i) => [cells[3 * i], cells[3 * i + 1], cells[3 * i + 2]]);
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
  // The number of cells at layer k and below.
  mesh.userData.cells = cells;
  mesh.userData.countUpTo = (k) => {
    let lo = 0, hi = n;
    while (lo < hi) {
      const mid = (lo + hi) >> 1;
      if (cells[3 * mid + 2] <= k) lo = mid + 1; else hi = mid;
    }
    return lo;
  };
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
  const sensor = data.sensor;  // the recorded one, or the default with a note (vantage view)
  const grid = data.grid;
  const extent = grid.dims.map((d) => d * grid.resolution);
  const center = new THREE.Vector3(...grid.origin.map((o, i) => o + extent[i] / 2));
  // NOTE: the sensor reaches metres past a table top; frusta drawn that long would hide it.
  const depth = Math.min(sensor.max_range, 0.8, Math.max(0.1, 0.3 * Math.max(...extent)));
  // Many candidates are drawn small, so that they do not cover the map.
  const mostCandidates = Math.max(1, ...data.decisions.map((d) => d.candidates.length));
  const candidateDepth = depth * Math.min(1, Math.max(0.3, Math.sqrt(30 / mostCandidates)));

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
  let occupiedMesh = null;
  if (occupied.cells.length > 0) {
    const colorOf = (k) => rampColor(THREE, kHeightRamp, zMax > zMin ? (k - zMin) / (zMax - zMin) : 0.5);
    occupiedMesh = cellMesh(THREE, data, occupied.cells,
                            new THREE.MeshBasicMaterial({vertexColors: true}), colorOf);
    scene.add(occupiedMesh);
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
    // The sensor's path as its carrier travelled it ([x, y]: an office's floor path of older files).
    let path = s.path.map(([x, y, z]) => new THREE.Vector3(x, y, z ?? grid.origin[2] + 0.02));
    if (path.length === 0 && i > 0) path = [new THREE.Vector3(...data.scans[i - 1].position), apex];
    if (path.length > 1) {
      const segments = path.slice(1).flatMap((p, j) => [path[j], p]);
      part.add(linesOf(THREE, segments, segments.map(() => new THREE.Color(kTaken))));
    }
    taken.add(part);
    return part;
  });

  // Candidates of the decision shown, coloured by what the method ranks them by; the chosen one
  // solid. The top-N slider keeps the best N by score (and the chosen one).
  const candidates = new THREE.Group();
  scene.add(candidates);
  const units = data.units;
  const topSlider = $('top-candidates');
  topSlider.max = String(mostCandidates);
  // NOTE: the attribute, not .value: the page's DOM then shows the setting (the headless check).
  topSlider.setAttribute('value', String(Math.min(mostCandidates, 100)));
  function showDecision(decision) {
    candidates.clear();
    $('gain-legend').style.display = decision ? '' : 'none';
    $('top-row').style.display = decision && decision.candidates.length > 1 ? '' : 'none';
    if (!decision || decision.candidates.length === 0) return;
    const scores = decision.candidates.map((c) => c.score);
    const lo = Math.min(...scores), hi = Math.max(...scores);
    const top = Math.min(Number(topSlider.value), decision.candidates.length);
    const ranked = decision.candidates.map((c, j) => j)
        .sort((a, b) => scores[b] - scores[a] || a - b).slice(0, top);
    const points = [], colors = [];
    for (const j of ranked) {
      if (j === decision.chosen) continue;
      const c = decision.candidates[j];
      const color = rampColor(THREE, kGainRamp, hi > lo ? (c.score - lo) / (hi - lo) : 1);
      const before = points.length;
      frustumLines(THREE, sensor, c, candidateDepth, points);
      for (let k = before; k < points.length; ++k) colors.push(color);
    }
    if (points.length > 0) candidates.add(linesOf(THREE, points, colors));
    const chosen = decision.candidates[decision.chosen];
    const [apex, ...c] = frustumCorners(THREE, sensor, chosen, depth);
    const sides = [];
    for (let i = 0; i < 4; ++i) sides.push(apex, c[i], c[(i + 1) % 4]);
    const solid = new THREE.BufferGeometry().setFromPoints(sides);
    candidates.add(new THREE.Mesh(solid, new THREE.MeshBasicMaterial({
      color: kChosen, side: THREE.DoubleSide})));
    const shown = ranked.includes(decision.chosen) ? top : top + 1;
    $('gain-title').textContent = `${data.ranked_by} of each candidate [${units.score}]: ` +
        `${shown} drawn of ${decision.total} candidates`;
    $('top-count').textContent = `${top} of ${decision.candidates.length}`;
    $('gain-min').textContent = format(lo, units.score);
    $('gain-max').textContent = format(hi, units.score);
  }

  // Numbers as the terminal prints them: explore's line (cells, no decimals), plan's table (one
  // decimal; latombe's and yamauchi's scores three).
  function describeChoice(decision, k) {
    const chosen = decision.candidates[decision.chosen];
    if (data.source === 'plan') {
      const scoreDigits = data.method === 'latombe' || data.method === 'yamauchi' ? 3 : 1;
      const parts = [`predicted gain ${fixed(chosen.gain, 1, units.gain)}`];
      if (chosen.cells !== null && units.gain !== 'cells') {
        parts.push(`predicted seen ${fixed(chosen.cells, 1, units.cells)}`);
      }
      parts.push(`greedy gain ${fixed(chosen.greedy, 1, units.greedy)}`);
      return `next best view: view ${chosen.view}, ${data.ranked_by} ` +
          `${fixed(chosen.score, scoreDigits, units.score)} (${parts.join(', ')})`;
    }
    const cells = chosen.cells ?? (units.gain === 'cells' ? chosen.gain : null);
    let text = `decision for scan ${k + 1}: view ${chosen.view}, predicted ` +
        `${fixed(cells, 0, units.cells)} (greedy ${fixed(chosen.greedy, 0, units.greedy)})`;
    if (units.score !== 'cells') {
      text += `; ranked by ${data.ranked_by}: ${fixed(chosen.score, 1, units.score)}`;
    }
    return text;
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
      text = describeChoice(decision, k);
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

  // From above: straight down on the grid's middle, the whole grid in sight.
  function viewFromAbove() {
    const reach = Math.max(extent[0], extent[1]) / 2 / Math.tan((camera.fov * Math.PI) / 360);
    controls.target.set(center.x, center.y, grid.origin[2]);
    // NOTE: a hair off vertical: OrbitControls cannot orbit from exactly above with z up.
    camera.position.set(center.x, center.y - reach * 1e-3, grid.origin[2] + extent[2] + reach * 1.1);
    controls.update();
    render();
  }

  // The height cut: cells above it are hidden, so a building's rooms show under its ceiling.
  const cut = $('height-cut');
  cut.min = '0';
  cut.max = String(grid.dims[2] - 1);
  cut.setAttribute('value', cut.max);
  function applyCut() {
    const k = Number(cut.value);
    for (const mesh of [occupiedMesh, unobservedMesh]) {
      if (mesh) mesh.count = mesh.userData.countUpTo(k);
    }
    $('height-cut-value').textContent = k >= grid.dims[2] - 1 ? 'none' :
        `cells above ${format(grid.origin[2] + (k + 1) * grid.resolution, 'm')} hidden`;
    render();
  }

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
  topSlider.addEventListener('input', update);
  cut.addEventListener('input', applyCut);
  $('top-view').addEventListener('click', viewFromAbove);
  $('show-candidates').addEventListener('change', (e) => { candidates.visible = e.target.checked; render(); });
  $('show-taken').addEventListener('change', (e) => { taken.visible = e.target.checked; render(); });
  $('show-unobserved').addEventListener('change', (e) => {
    if (unobservedMesh) unobservedMesh.visible = e.target.checked;
    render();
  });

  const inputs = data.source === 'plan'
      ? (data.clouds === null ? 'clouds not recorded' :
         `${data.clouds} ${data.clouds === 1 ? 'cloud' : 'clouds'}`)
      : `${data.scans.length} ${data.scans.length === 1 ? 'scan' : 'scans'}`;
  $('summary').textContent = `${occupied.total} occupied cells of ${grid.resolution} m; ` +
      `${inputs}; three.js ${data.three_version}`;
  $('notes').replaceChildren(...notes.map((n) => {
    const div = document.createElement('div');
    div.textContent = n;
    return div;
  }));
  // The page's address can set the view: #cut=2.0 hides the cells above 2.0 m, #above looks
  // from above (view.html#cut=2.0&above), so a building's picture can be made headless.
  const hash = new URLSearchParams(window.location.hash.slice(1));
  if (hash.has('cut')) {
    const k = Math.ceil((Number(hash.get('cut')) - grid.origin[2]) / grid.resolution) - 1;
    if (Number.isFinite(k)) cut.setAttribute('value', String(Math.min(Math.max(k, 0), grid.dims[2] - 1)));
  }
  applyCut();
  if (hash.has('above')) viewFromAbove();
  update();
  if (window.vantageErrors.length === 0) {
    $('status').dataset.state = 'ready';
    $('status').textContent = 'ready';
  }
}

main().catch((e) => vantageFail(e && e.stack ? e.stack : e));
