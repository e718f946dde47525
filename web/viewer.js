// The 3-D view of `towsim report`: bundled with three.js by esbuild at build
// time (web/package.json) and inlined into report.html, so the page needs no
// network. Reads the run from <script id="towsim-data" type="application/json">.
//
// towsim's frame R_g is x, y horizontal and z up; three.js has y up. A point
// (x, y, z) is drawn at (x, z, -y): a rotation, so handedness is kept.
//
// When the first frame is drawn the page's <html> element gets
// data-ready="1" and data-drawn-pixels (pixels of the canvas that differ from
// the background), which the headless-browser test reads; a script error sets
// data-error.
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';

const root = document.documentElement;
window.addEventListener('error', (e) => root.setAttribute('data-error', String(e.message || e)));

/// towsim (x, y, z) -> three.js vector.
const v3 = (x, y, z) => new THREE.Vector3(x, z, -y);

/// Rotation body -> global, R = Rz(yaw) Ry(pitch) Rx(roll), as a three.js
/// quaternion in the three.js frame: M R M^T with M the axis map above.
function attitude(rollDeg, pitchDeg, yawDeg) {
  const d = Math.PI / 180;
  const [cr, sr, cp, sp, cy, sy] = [Math.cos(rollDeg * d), Math.sin(rollDeg * d), Math.cos(pitchDeg * d),
    Math.sin(pitchDeg * d), Math.cos(yawDeg * d), Math.sin(yawDeg * d)];
  const R = [
    [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
    [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
    [-sp, cp * sr, cp * cr],
  ];
  const M = [[1, 0, 0], [0, 0, 1], [0, -1, 0]];
  const A = [[0, 0, 0], [0, 0, 0], [0, 0, 0]];
  for (let i = 0; i < 3; i++)
    for (let j = 0; j < 3; j++)
      for (let k = 0; k < 3; k++)
        for (let l = 0; l < 3; l++) A[i][j] += M[i][k] * R[k][l] * M[j][l];
  const m = new THREE.Matrix4().set(A[0][0], A[0][1], A[0][2], 0, A[1][0], A[1][1], A[1][2], 0,
    A[2][0], A[2][1], A[2][2], 0, 0, 0, 0, 1);
  return new THREE.Quaternion().setFromRotationMatrix(m);
}

/// Colour of a tension t in [0, tmax] on a viridis-like ramp.
function ramp(f, out) {
  const stops = [[68, 1, 84], [59, 82, 139], [33, 145, 140], [94, 201, 98], [253, 231, 37]];
  const s = Math.min(Math.max(f, 0), 1) * 4, i = Math.min(3, Math.floor(s)), g = s - i;
  out.setRGB((stops[i][0] + g * (stops[i + 1][0] - stops[i][0])) / 255,
    (stops[i][1] + g * (stops[i + 1][1] - stops[i][1])) / 255,
    (stops[i][2] + g * (stops[i + 1][2] - stops[i][2])) / 255);
  return out;
}

function main() {
  const data = JSON.parse(document.getElementById('towsim-data').textContent);
  const host = document.getElementById('view3d');
  const F = data.times.length, N = data.nodes[0].length / 3;

  // The framing (report.cpp): each frame's cable-and-body centre, the largest
  // extent the cable takes (the view follows the cable at that zoom), and the
  // whole run's centre and extent (the "Whole run" view).
  const view = data.view;
  const centreAt = (i) => { const c = view.cable_centres[i]; return v3(c[0], c[1], c[2]); };
  const cableExtent = Math.max(view.cable_extent, 1e-3), allExtent = Math.max(view.all_extent, cableExtent);
  const allCentre = v3(view.all_centre[0], view.all_centre[1], view.all_centre[2]);

  const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  renderer.setSize(host.clientWidth, host.clientHeight);
  renderer.setClearColor(0xeef3f8);
  host.appendChild(renderer.domElement);
  const scene = new THREE.Scene();
  scene.add(new THREE.AmbientLight(0xffffff, 0.7));
  const sun = new THREE.DirectionalLight(0xffffff, 1.6);
  sun.position.set(1, 2, 1.5);
  scene.add(sun);

  // Near enough to look at a body of a metre from a few metres, far enough
  // for the whole run.
  const camera = new THREE.PerspectiveCamera(40, host.clientWidth / host.clientHeight,
    Math.min(0.05, cableExtent * 1e-4), allExtent * 100);
  const controls = new OrbitControls(camera, renderer.domElement);
  // Just far enough for a sphere of diameter `extent` to fit the view, looking
  // from 25 degrees above the horizontal, across the tow direction.
  function frameOn(centre, extent) {
    const dist = (0.5 * extent) / Math.sin((0.5 * 40 * Math.PI) / 180);
    const el = (25 * Math.PI) / 180;
    camera.position.copy(centre).add(new THREE.Vector3(0.45 * dist * Math.cos(el), dist * Math.sin(el),
      0.9 * dist * Math.cos(el)));
    controls.target.copy(centre);
    controls.update();
  }

  // Sea surface (z = 0) and a grid on it, over the whole run.
  const allBox = new THREE.Box3();
  for (const fr of data.nodes)
    for (let k = 0; k < N; k++) allBox.expandByPoint(v3(fr[3 * k], fr[3 * k + 1], fr[3 * k + 2]));
  const allSize = allBox.getSize(new THREE.Vector3());
  const span = 1.3 * Math.max(allSize.x, allSize.z, cableExtent);
  const sea = new THREE.Mesh(new THREE.PlaneGeometry(span, span),
    new THREE.MeshBasicMaterial({ color: 0x4f8fc0, transparent: true, opacity: 0.15, side: THREE.DoubleSide,
      depthWrite: false }));
  sea.rotation.x = -Math.PI / 2;
  sea.position.set(allCentre.x, 0, allCentre.z);
  scene.add(sea);
  const grid = new THREE.GridHelper(span, 10, 0x7aa6c8, 0xa9c6dc);
  grid.position.set(allCentre.x, 0, allCentre.z);
  scene.add(grid);

  // The tow point's path over the whole run.
  const towPath = new THREE.BufferGeometry().setFromPoints(
    data.nodes.map((fr) => v3(fr[0], fr[1], fr[2])));
  scene.add(new THREE.Line(towPath, new THREE.LineBasicMaterial({ color: 0x888888 })));

  // The cable: a line coloured by tension, and its joints.
  const pos = new Float32Array(3 * N), col = new Float32Array(3 * N);
  const cableGeom = new THREE.BufferGeometry();
  cableGeom.setAttribute('position', new THREE.BufferAttribute(pos, 3));
  cableGeom.setAttribute('color', new THREE.BufferAttribute(col, 3));
  // A network's lines one after the other: segments, broken where a line starts.
  const cableMaterial = new THREE.LineBasicMaterial({ vertexColors: true });
  if (data.breaks && data.breaks.length) {
    const starts = new Set(data.breaks), segments = [];
    for (let k = 0; k + 1 < N; k++) if (!starts.has(k + 1)) segments.push(k, k + 1);
    const lines = new THREE.BufferGeometry();
    lines.setAttribute('position', cableGeom.attributes.position);
    lines.setAttribute('color', cableGeom.attributes.color);
    lines.setIndex(segments);
    const drawn = new THREE.LineSegments(lines, cableMaterial);
    drawn.frustumCulled = false;  // its positions move with every frame
    scene.add(drawn);
  } else {
    scene.add(new THREE.Line(cableGeom, cableMaterial));
  }
  scene.add(new THREE.Points(cableGeom, new THREE.PointsMaterial({ vertexColors: true, size: 4,
    sizeAttenuation: false })));
  const tow = new THREE.Mesh(new THREE.SphereGeometry(cableExtent * 0.008, 16, 12),
    new THREE.MeshLambertMaterial({ color: 0xd62728 }));
  scene.add(tow);

  // The bodies at their true size (metres, body axes): their load spheres,
  // hull cylinders and fins (squares of their area); a dot of constant size
  // on the screen marks where each is when it is too small to see. A chain
  // has one (data.body), a network any number (data.bodies).
  const bodyData = data.bodies || (data.body ? [data.body] : []);
  const mat = new THREE.MeshLambertMaterial({ color: 0xff7f0e });
  const finMat = new THREE.MeshLambertMaterial({ color: 0xb85c00, side: THREE.DoubleSide });
  const B = (p) => v3(p[0], p[1], p[2]);
  function makeBody(d) {
    const group = new THREE.Group();
    for (const s of d.spheres) {
      const m = new THREE.Mesh(new THREE.SphereGeometry(s.radius, 24, 16), mat);
      m.position.copy(B(s.center));
      group.add(m);
    }
    for (const c of d.cylinders) {
      // CylinderGeometry runs along y: turn y onto the cylinder's axis.
      const m = new THREE.Mesh(new THREE.CylinderGeometry(0.5 * c.diameter, 0.5 * c.diameter, c.length, 24), mat);
      m.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), B(c.axis).normalize());
      m.position.copy(B(c.center));
      group.add(m);
    }
    for (const f of d.surfaces) {
      // A square of the fin's area in its plane (chord and normal x chord).
      const side = Math.sqrt(f.area), x = B(f.chord).normalize(), n = B(f.normal).normalize();
      const y = new THREE.Vector3().crossVectors(n, x).normalize();
      const m = new THREE.Mesh(new THREE.PlaneGeometry(side, side), finMat);
      m.quaternion.setFromRotationMatrix(new THREE.Matrix4().makeBasis(x, y, n));
      m.position.copy(B(f.center));
      group.add(m);
    }
    const shapes = group.children.length > 0;
    if (!shapes) group.add(new THREE.Mesh(new THREE.SphereGeometry(0.5, 24, 16), mat));  // no shapes: a 1 m ball
    const size = new THREE.Box3().setFromObject(group).getSize(new THREE.Vector3());
    const length = Math.max(size.x, size.y, size.z);
    group.add(new THREE.AxesHelper(0.75 * length));  // body axes: x red, y green, z blue (three.js frame)
    scene.add(group);
    const dot = new THREE.BufferGeometry().setFromPoints([new THREE.Vector3()]);
    const marker = new THREE.Points(dot, new THREE.PointsMaterial({ color: 0xff7f0e, size: 7, sizeAttenuation: false }));
    scene.add(marker);
    return { d, group, marker, shapes, length, size };
  }
  const bodies = bodyData.map(makeBody);
  const body = bodies.length ? bodies[0] : null;
  // towsim axes of the (first) body (three.js x, y, z = towsim x, z, -y).
  if (body) root.setAttribute('data-body-size', [body.size.x, body.size.z, body.size.y].map((v) => v.toPrecision(6)).join(','));
  const bodyShapes = body ? body.shapes : false, bodyLength = body ? body.length : 0;
  const tmax = Math.max(data.tension_max || 0, 1e-12);
  const c = new THREE.Color();

  // The controls.
  const slider = document.getElementById('frame'), label = document.getElementById('frame-label');
  const play = document.getElementById('play');
  slider.max = String(F - 1);
  const fit = document.getElementById('fit');
  document.getElementById('scale-note').textContent =
    (bodies.length > 1 ? `${bodies.length} bodies drawn at their true size, each marked by an orange dot. ` :
      body ? (bodyShapes ? `Body drawn at its true size (${bodyLength.toPrecision(3)} m), marked by an orange dot. `
      : 'Body: the scenario gives no shape; drawn as a 1 m ball, marked by an orange dot. ') : '') +
    `Cable coloured by tension, 0 to ${tmax.toPrecision(4)} N (dark blue to yellow). ` +
    'The view follows the cable; "Whole run" shows the whole track. Drag to rotate, scroll to zoom.';

  function show(i) {
    const fr = data.nodes[i], T = data.tension[i];
    for (let k = 0; k < N; k++) {
      const p = v3(fr[3 * k], fr[3 * k + 1], fr[3 * k + 2]);
      pos[3 * k] = p.x; pos[3 * k + 1] = p.y; pos[3 * k + 2] = p.z;
      ramp((T ? T[k] : 0) / tmax, c);
      col[3 * k] = c.r; col[3 * k + 1] = c.g; col[3 * k + 2] = c.b;
    }
    cableGeom.attributes.position.needsUpdate = true;
    cableGeom.attributes.color.needsUpdate = true;
    cableGeom.computeBoundingSphere();
    tow.position.copy(v3(fr[0], fr[1], fr[2]));
    for (const b of bodies) {
      const p = b.d.pos[i], a = b.d.rpy[i];
      b.group.position.copy(v3(p[0], p[1], p[2]));
      b.group.quaternion.copy(attitude(a[0], a[1], a[2]));
      b.marker.position.copy(b.group.position);
    }
    if (following) {  // keep the camera where the user turned it, relative to the cable
      const d = centreAt(i).sub(controls.target);
      camera.position.add(d);
      controls.target.add(d);
    }
    label.textContent = `t = ${data.times[i]} s` + (data.info ? '  ' + data.info[i] : '');
  }

  let frame = 0, playing = false, last = 0, following = true;
  fit.addEventListener('click', () => {
    following = !following;
    fit.textContent = following ? 'Whole run' : 'Follow the cable';
    if (following) frameOn(centreAt(frame), cableExtent); else frameOn(allCentre, allExtent);
  });
  slider.addEventListener('input', () => { frame = Number(slider.value); show(frame); });
  play.addEventListener('click', () => {
    playing = !playing;
    play.textContent = playing ? 'Pause' : 'Play';
    if (playing && frame >= F - 1) frame = 0;
  });
  window.addEventListener('resize', () => {
    camera.aspect = host.clientWidth / host.clientHeight;
    camera.updateProjectionMatrix();
    renderer.setSize(host.clientWidth, host.clientHeight);
  });
  // About 20 s for the whole run.
  const perFrame = 20000 / Math.max(F, 1);
  function loop(now) {
    requestAnimationFrame(loop);
    if (playing && now - last > perFrame) {
      last = now;
      frame = Math.min(F - 1, frame + 1);
      slider.value = String(frame);
      show(frame);
      if (frame === F - 1) { playing = false; play.textContent = 'Play'; }
    }
    controls.update();
    renderer.render(scene, camera);
  }
  // report.html#t=20 opens at the frame nearest t = 20 s.
  const want = /[#&]t=([-0-9.eE+]+)/.exec(window.location.hash);
  if (want) {
    let best = 0;
    for (let i = 0; i < F; i++)
      if (Math.abs(data.times[i] - Number(want[1])) < Math.abs(data.times[best] - Number(want[1]))) best = i;
    frame = best;
    slider.value = String(frame);
  }
  frameOn(centreAt(frame), cableExtent);
  show(frame);
  renderer.render(scene, camera);

  // How much of the view the cable's frame takes: the larger of the widths
  // and heights of its joints' screen box, as fractions of the view's.
  let x0 = 1, x1 = -1, y0 = 1, y1 = -1;
  for (let k = 0; k < N; k++) {
    const q = new THREE.Vector3(pos[3 * k], pos[3 * k + 1], pos[3 * k + 2]).project(camera);
    x0 = Math.min(x0, q.x); x1 = Math.max(x1, q.x); y0 = Math.min(y0, q.y); y1 = Math.max(y1, q.y);
  }
  root.setAttribute('data-cable-view-fraction', (0.5 * Math.max(x1 - x0, y1 - y0)).toFixed(3));

  // The first frame is drawn: count the pixels that are not background.
  const gl = renderer.getContext();
  const w = gl.drawingBufferWidth, h = gl.drawingBufferHeight;
  const px = new Uint8Array(4 * w * h);
  gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, px);
  let drawn = 0;
  for (let i = 0; i < px.length; i += 4)
    if (Math.abs(px[i] - 0xee) + Math.abs(px[i + 1] - 0xf3) + Math.abs(px[i + 2] - 0xf8) > 12) drawn++;
  root.setAttribute('data-drawn-pixels', String(drawn));
  root.setAttribute('data-ready', '1');
  document.title = document.title + ' (3-D view ready)';
  requestAnimationFrame(loop);
}

try {
  main();
} catch (e) {
  root.setAttribute('data-error', String(e && e.message ? e.message : e));
  const host = document.getElementById('view3d');
  if (host) host.textContent = 'The 3-D view could not start: ' + (e && e.message ? e.message : e);
  throw e;
}
