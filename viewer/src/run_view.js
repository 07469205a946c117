// One run drawn with three.js in one canvas: the surface, and the overlays of
// seed 001's visual debugging (border points, penetration vectors, tet boxes,
// the hash grid), one to four views of it.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { judgedPoints } from './replay.js';

const BODY_COLOURS = [0x8fa8c8, 0xc8a88f, 0x9fc88f, 0xc88fb8, 0xc8c38f, 0x8fc8c3];
export const FORCE_COLOURS = { computed: 0x1f77b4, held: 0x17becf, extrapolated: 0xff7f0e, tracked: 0x9467bd, none: 0x7f7f7f };
export const VERDICT_COLOURS = { correct: 0x2ca02c, missed: 0xd62728, false: 0xe6c700, touching: 0x8c564b, unjudged: 0x7f7f7f };
const FORCE_BY_CODE = { 0: 'computed', 1: 'held', 2: 'extrapolated', 3: 'tracked', 255: 'none' };
// Where a point's depth came from (the replay's depth_source): seed 001's
// border points are those whose depth was found at the border.
export const DEPTH_COLOURS = { border: 0x1f77b4, propagated: 0x2ca02c, tet_pair: 0x9467bd, none: 0x7f7f7f, 'not held': 0xd62728 };
const DEPTH_BY_CODE = { 0: 'none', 1: 'border', 2: 'propagated', 3: 'tet_pair' };

// The 12 edges of a box as pairs of corner indices (corner bits: x, y, z).
const BOX_EDGES = [[0, 1], [2, 3], [4, 5], [6, 7], [0, 2], [1, 3], [4, 6], [5, 7], [0, 4], [1, 5], [2, 6], [3, 7]];
const MAX_GRID_CELLS = 200000;

function boxLines(out, at, lo, hi) {
  for (const [a, b] of BOX_EDGES) {
    for (const c of [a, b]) {
      out[at++] = c & 1 ? hi[0] : lo[0];
      out[at++] = c & 2 ? hi[1] : lo[1];
      out[at++] = c & 4 ? hi[2] : lo[2];
    }
  }
  return at;
}

export class RunView {
  // replay: { bodies, triangles, surfaceMap, vertexCount }; container: a DOM element.
  constructor(container, replay, title) {
    this.container = container;
    this.replay = replay;
    this.overlays = { wireframe: false, points: true, vectors: true, boxes: false, grid: false, fourViews: false };
    this.colourBy = 'force';
    this.vectorScale = 1;
    this.renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(1);
    this.renderer.setClearColor(0xf4f4f4);
    this.renderer.autoClear = false;
    container.appendChild(this.renderer.domElement);
    this.label = document.createElement('div');
    this.label.className = 'view-title';
    this.label.textContent = title;
    container.appendChild(this.label);

    this.scene = new THREE.Scene();
    this.scene.add(new THREE.HemisphereLight(0xffffff, 0x606070, 2.2));
    const sun = new THREE.DirectionalLight(0xffffff, 1.2);
    sun.position.set(1, 2, 3);
    this.scene.add(sun);

    const geometry = new THREE.BufferGeometry();
    this.positionAttribute = new THREE.BufferAttribute(new Float32Array(replay.vertexCount * 3), 3);
    this.positionAttribute.setUsage(THREE.DynamicDrawUsage);
    geometry.setAttribute('position', this.positionAttribute);
    const colours = new Float32Array(replay.vertexCount * 3);
    const colour = new THREE.Color();
    for (let v = 0; v < replay.vertexCount; ++v) {
      colour.setHex(BODY_COLOURS[replay.surfaceMap[2 * v] % BODY_COLOURS.length]);
      colours.set([colour.r, colour.g, colour.b], 3 * v);
    }
    geometry.setAttribute('color', new THREE.BufferAttribute(colours, 3));
    geometry.setIndex(new THREE.BufferAttribute(replay.triangles, 1));
    this.material = new THREE.MeshStandardMaterial({ vertexColors: true, roughness: 0.8, side: THREE.DoubleSide,
      transparent: true, opacity: 0.85, polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1 });
    this.mesh = new THREE.Mesh(geometry, this.material);
    this.scene.add(this.mesh);

    this.points = new THREE.Points(new THREE.BufferGeometry(),
      new THREE.PointsMaterial({ size: 8, sizeAttenuation: false, vertexColors: true, depthTest: false, transparent: true }));
    // Drawn last and through the surface: the points sit inside the bodies.
    this.points.renderOrder = 2;
    this.vectors = new THREE.LineSegments(new THREE.BufferGeometry(),
      new THREE.LineBasicMaterial({ vertexColors: true, depthTest: false, transparent: true }));
    this.vectors.renderOrder = 2;
    this.boxes = new THREE.LineSegments(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({ color: 0x3050a0, transparent: true, opacity: 0.35 }));
    this.grid = new THREE.LineSegments(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({ color: 0xa03030, transparent: true, opacity: 0.45 }));
    for (const o of [this.points, this.vectors, this.boxes, this.grid]) this.scene.add(o);

    this.camera = new THREE.PerspectiveCamera(40, 1, 1e-4, 1e4);
    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.addEventListener('change', () => {
      this.render();
      if (this.onCameraChange && !this.syncing) this.onCameraChange(this);
    });
    this.orthoCameras = [0, 1, 2].map(() => new THREE.OrthographicCamera(-1, 1, 1, -1, -1e4, 1e4));
    this.frame = null;
    this.stats = { points: 0, verdicts: {} };
    // The plot under the views grows as its panels appear: follow the box.
    new ResizeObserver(() => this.resize()).observe(container);
  }

  // Frames the camera on the first frame's surface.
  fitCamera(frame) {
    const box = new THREE.Box3().setFromArray(frame.positions);
    const centre = box.getCenter(new THREE.Vector3());
    const radius = Math.max(box.getSize(new THREE.Vector3()).length() / 2, 1e-6);
    this.radius = radius;
    this.camera.near = radius / 1000;
    this.camera.far = radius * 100;
    this.camera.position.copy(centre).add(new THREE.Vector3(0.9, 0.6, 1.6).multiplyScalar(radius * 1.6));
    this.controls.target.copy(centre);
    this.camera.updateProjectionMatrix();
    this.controls.update();
    // Front (looking along -z), side (along -x), top (along -y).
    const offsets = [[0, 0, 1], [1, 0, 0], [0, 1, 0]];
    this.orthoCameras.forEach((c, i) => {
      c.position.copy(centre).add(new THREE.Vector3(...offsets[i]).multiplyScalar(radius * 10));
      if (i === 2) c.up.set(0, 0, -1);
      c.lookAt(centre);
    });
  }

  showFrame(frame) {
    if (!this.frame) this.fitCamera(frame);
    this.frame = frame;
    this.positionAttribute.array.set(frame.positions);
    this.positionAttribute.needsUpdate = true;
    this.mesh.geometry.computeVertexNormals();
    this.mesh.geometry.computeBoundingSphere();
    this.updateOverlays();
  }

  updateOverlays() {
    const frame = this.frame;
    if (!frame) return;
    this.material.wireframe = this.overlays.wireframe;
    this.material.opacity = this.overlays.wireframe ? 1 : 0.85;
    const judged = judgedPoints(frame);
    const pointPositions = new Float32Array(judged.length * 3);
    const pointColours = new Float32Array(judged.length * 3);
    const vectorPositions = [];
    const vectorColours = [];
    const colour = new THREE.Color();
    const verdicts = {};
    judged.forEach((p, i) => {
      pointPositions.set(p.position, 3 * i);
      const name = this.colourBy === 'oracle' ? (p.verdict ?? 'unjudged')
        : this.colourBy === 'depth' ? (p.method ? DEPTH_BY_CODE[p.depthSource] ?? 'none' : 'not held')
          : FORCE_BY_CODE[p.force] ?? 'none';
      verdicts[name] = (verdicts[name] ?? 0) + 1;
      colour.setHex((this.colourBy === 'oracle' ? VERDICT_COLOURS : this.colourBy === 'depth' ? DEPTH_COLOURS : FORCE_COLOURS)[name]);
      pointColours.set([colour.r, colour.g, colour.b], 3 * i);
      if (p.direction && Number.isFinite(p.depth)) {
        const length = p.depth * this.vectorScale;
        vectorPositions.push(...p.position, ...p.position.map((x, k) => x + p.direction[k] * length));
        vectorColours.push(colour.r, colour.g, colour.b, colour.r, colour.g, colour.b);
      }
    });
    this.stats = { points: judged.length, verdicts, oracle: !!frame.oracle };
    this.judged = judged;
    const setPoints = (object, positions, colours) => {
      object.geometry.dispose();
      object.geometry = new THREE.BufferGeometry();
      object.geometry.setAttribute('position', new THREE.BufferAttribute(positions, 3));
      if (colours) object.geometry.setAttribute('color', new THREE.BufferAttribute(colours, 3));
    };
    setPoints(this.points, pointPositions, pointColours);
    setPoints(this.vectors, new Float32Array(vectorPositions), new Float32Array(vectorColours));
    this.points.visible = this.overlays.points;
    this.vectors.visible = this.overlays.vectors;

    this.boxes.visible = this.overlays.boxes && !!frame.aabbs;
    if (this.boxes.visible) {
      const n = frame.aabbs.length / 6;
      const lines = new Float32Array(n * 72);
      let at = 0;
      for (let t = 0; t < n; ++t) at = boxLines(lines, at, frame.aabbs.subarray(6 * t, 6 * t + 3), frame.aabbs.subarray(6 * t + 3, 6 * t + 6));
      setPoints(this.boxes, lines, null);
    }
    this.grid.visible = this.overlays.grid && !!frame.cells && !!this.replay.cellSize;
    if (this.grid.visible) {
      const h = this.replay.cellSize;
      const n = Math.min(frame.cells.length / 3, MAX_GRID_CELLS);
      const lines = new Float32Array(n * 72);
      let at = 0;
      for (let c = 0; c < n; ++c) {
        const lo = [0, 1, 2].map((k) => frame.cells[3 * c + k] * h);
        at = boxLines(lines, at, lo, lo.map((x) => x + h));
      }
      setPoints(this.grid, lines, null);
    }
    this.render();
  }

  // Seed 001's picking: the point drawn nearest the cursor (within 8 px) at
  // canvas pixel (x, y), or null. Screen distance, so a point inside a body
  // is found where it is drawn.
  pick(x, y) {
    if (!this.judged || !this.overlays.points || this.overlays.fourViews) return null;
    const width = this.renderer.domElement.clientWidth;
    const height = this.renderer.domElement.clientHeight;
    let best = null;
    let bestDistance = 8;
    const v = new THREE.Vector3();
    for (const p of this.judged) {
      v.set(...p.position).project(this.camera);
      const distance = Math.hypot((v.x + 1) / 2 * width - x, (1 - v.y) / 2 * height - y);
      if (distance < bestDistance) { best = p; bestDistance = distance; }
    }
    return best;
  }

  resize() {
    const width = this.container.clientWidth;
    const height = this.container.clientHeight;
    this.renderer.setSize(width, height, false);
    this.renderer.domElement.style.width = `${width}px`;
    this.renderer.domElement.style.height = `${height}px`;
    this.render();
  }

  render() {
    const size = this.renderer.getSize(new THREE.Vector2());
    const w = size.x;
    const h = size.y;
    if (w === 0 || h === 0) return;
    this.renderer.setScissorTest(true);
    this.renderer.setScissor(0, 0, w, h);
    this.renderer.setViewport(0, 0, w, h);
    this.renderer.clear();
    if (!this.overlays.fourViews) {
      this.camera.aspect = w / h;
      this.camera.updateProjectionMatrix();
      this.renderer.render(this.scene, this.camera);
      return;
    }
    // Seed 001's four views: front, side, top and the orbiting camera.
    const hw = Math.floor(w / 2);
    const hh = Math.floor(h / 2);
    const cells = [[0, hh], [hw, hh], [0, 0], [hw, 0]];
    const r = (this.radius ?? 1) * 1.2;
    cells.forEach(([x, y], i) => {
      this.renderer.setScissor(x + 1, y + 1, hw - 2, hh - 2);
      this.renderer.setViewport(x, y, hw, hh);
      this.renderer.clear();
      if (i < 3) {
        const c = this.orthoCameras[i];
        const aspect = hw / hh;
        Object.assign(c, { left: -r * aspect, right: r * aspect, top: r, bottom: -r });
        c.updateProjectionMatrix();
        this.renderer.render(this.scene, c);
      } else {
        this.camera.aspect = hw / hh;
        this.camera.updateProjectionMatrix();
        this.renderer.render(this.scene, this.camera);
      }
    });
  }
}
