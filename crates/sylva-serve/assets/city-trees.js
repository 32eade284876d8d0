// A city's trees as the view draws them. Every instanced mesh of a loaded tile is kept as data
// (each tree's matrix, its row of the tile's property table, its colour under the filters) and
// not drawn itself: each frame the trees the camera sees, from every tile shown, are gathered
// into one instanced mesh per grown tree, its bark and leaves made one mesh (`combine`,
// `Batches`). A view over a few blocks then costs a draw per species and age class in it
// rather than two per class in each
// of its tiles (hundreds), and draws only the trees in view, not every tree of tiles some 600 m
// across. A browser drawing WebGL on its CPU pays most for its draws. Picking and colouring go
// through the gathering, so a tree is always its own row.

import * as T from '/vendor/city.min.js';

const frustum = new T.Frustum();
const toLocal = new T.Matrix4();
const world = new T.Matrix4();
const fromWorld = new T.Matrix4();
const eyeHere = new T.Vector3();
const centre = new T.Vector3();

// A tree whose crown would be drawn narrower than this, in drawn pixels, is drawn as a marker
// in its species' colour instead: a crown a pixel or two wide shows as nothing (a census
// sample of 138 trees over 2.4 km opened on empty ground), a marker a few pixels wide shows
// every tree of a sparse inventory and the streets of a dense one. (Sylva's choice.)
export const MARKER_PIXELS = 3;
// The name of a coarse tile's points, the trees it leaves out of its meshes (`sylva city`'s
// `tiles::content::LEFT_OUT`).
export const LEFT_OUT = 'left-out';
// A marker's size on the screen, CSS pixels.
const MARKER_SIZE = 5;

// Colours by species for the markers and the legend: Okabe & Ito's eight colours, told apart
// by readers with any common colour-vision deficiency (Okabe & Ito 2008, "Color Universal
// Design"), for the most common species first; every other species in white.
export const PALETTE = ['#E69F00', '#56B4E9', '#009E73', '#F0E442', '#0072B2', '#D55E00', '#CC79A7', '#000000'];
export const OTHER_SPECIES = '#FFFFFF';
let palette = new Map();  // species code -> [r, g, b], linear
let paletteVersion = 0;
const other = new T.Color(OTHER_SPECIES);

// The species whose markers take the palette's colours, most common first (the rest: white).
export function setSpeciesColours(codes) {
  palette = new Map(codes.slice(0, PALETTE.length).map((c, i) => {
    const colour = new T.Color(PALETTE[i]);
    return [c, [colour.r, colour.g, colour.b]];
  }));
  paletteVersion++;
}

// Tiles share the grown trees' meshes: every tile that draws a species' age class at a level
// names the same file of `prototypes/`, and its instanced meshes are named by that file's
// stem and the primitive (`PLAC-InlVal-25-0-L2_1`, its bark; `_2`, its leaves). With three.js's
// file cache on, each file is fetched once; `share` then gives every tile the first geometry
// made under that name, so that each mesh reaches the GPU once however many tiles draw it,
// and the trees of all tiles that draw it gather into one batch below.
const shared = new Map();  // mesh name -> geometry

export function share(mesh) {
  const first = shared.get(mesh.name);
  if (!first) { shared.set(mesh.name, mesh.geometry); return; }
  if (first !== mesh.geometry) {
    mesh.geometry.dispose();
    mesh.geometry = first;
  }
}

// Forgets the shared meshes (another city's names may mean other trees).
export function forget() {
  shared.clear();
  for (const m of impostors.values()) { m.map?.dispose(); m.dispose(); }
  impostors.clear();
  for (const g of merged.values()) g.dispose();
  merged.clear();
}

// A grown tree is two meshes in a tile, its bark and its leaves, with the same trees: drawn
// apart, they cost two draws per species and age class in view, and a browser drawing on its
// CPU spends most of a frame on its draws (a 100,000-tree city turned at 7 frames a second,
// 12 with half the draws). `combine` makes them one mesh, each part's colour (its material's
// times its vertices') carried by its vertices, drawn with one matte two-sided material (a CPU
// drawing WebGL fills a Lambert pixel several times faster than a physically based one); the
// first part's trees then stand for the tree, and the other parts are data only.
const merged = new Map();  // the parts' meshes and colours -> their merged mesh
export const TREE_MATERIAL = new T.MeshLambertMaterial({ vertexColors: true, side: 2 /* DoubleSide */ });

function mergedOf(parts) {
  // Tiles share their meshes (`share`), not their materials: a part's colour is the key.
  const key = parts.map((p) => `${p.geometry.uuid}/${p.material.color.toArray().join(',')}`).join('|');
  let geometry = merged.get(key);
  if (geometry) return geometry;
  let vertices = 0;
  for (const p of parts) vertices += p.geometry.getAttribute('position').count;
  const position = new Float32Array(3 * vertices), normal = new Float32Array(3 * vertices);
  const colour = new Float32Array(3 * vertices);
  const index = [];
  let v = 0;
  for (const p of parts) {
    const g = p.geometry, at = g.getAttribute('position'), n = g.getAttribute('normal');
    const vc = g.getAttribute('color'), c = p.material.color;
    for (let i = 0; i < at.count; i++) {
      const k = 3 * (v + i);
      position[k] = at.getX(i); position[k + 1] = at.getY(i); position[k + 2] = at.getZ(i);
      if (n) { normal[k] = n.getX(i); normal[k + 1] = n.getY(i); normal[k + 2] = n.getZ(i); }
      colour[k] = c.r * (vc ? vc.getX(i) : 1);
      colour[k + 1] = c.g * (vc ? vc.getY(i) : 1);
      colour[k + 2] = c.b * (vc ? vc.getZ(i) : 1);
    }
    if (g.index) for (let i = 0; i < g.index.count; i++) index.push(v + g.index.getX(i));
    else for (let i = 0; i < at.count; i++) index.push(v + i);
    v += at.count;
  }
  geometry = new T.BufferGeometry();
  geometry.setAttribute('position', new T.Float32BufferAttribute(position, 3));
  geometry.setAttribute('normal', new T.Float32BufferAttribute(normal, 3));
  geometry.setAttribute('color', new T.Float32BufferAttribute(colour, 3));
  geometry.setIndex(index);
  geometry.computeBoundingSphere();
  merged.set(key, geometry);
  return geometry;
}

// Makes each tree of a loaded tile (`root`) one mesh: the parts of one glTF node are the
// instanced meshes of one parent named by the node and their primitive (`…-L2_1`, `…-L2_2`),
// with as many trees.
export function combine(root) {
  const trees = new Map();
  root.traverse((o) => {
    if (!o.isInstancedMesh) return;
    const key = `${o.parent?.uuid}|${o.name.replace(/_\d+$/, '')}|${o.count}`;
    if (!trees.has(key)) trees.set(key, []);
    trees.get(key).push(o);
  });
  for (const parts of trees.values()) {
    const s = prepare(parts[0]);
    if (s.merged) continue;
    const atlas = parts.length === 1 && parts[0].material.map;
    if (atlas) {
      // A far tile's impostor: its quads and its unlit, alpha-masked atlas, drawn as they came.
      s.merged = parts[0].geometry;
      if (!s.merged.boundingSphere) s.merged.computeBoundingSphere();
      s.material = impostorMaterial(parts[0].material);
    } else {
      s.merged = mergedOf(parts);
    }
    s.spheres = spheresOf(parts[0], s.merged.boundingSphere);
  }
}

// Impostors' materials by name (each names its picture: a city's, which holds every grown
// tree's views, or in cities written before it one per tree): tiles that draw the same picture
// then share one material and one texture on the GPU.
const impostors = new Map();

function impostorMaterial(material) {
  let kept = impostors.get(material.name);
  if (kept) return kept;
  // The tiles renderer closes a tile's pictures when it drops the tile, so the kept material
  // draws from its own copy of the atlas: a clone of the tile's texture (flip, colour space,
  // filters) over a canvas of its pixels, with a source of its own.
  const atlas = material.map.image;
  const canvas = document.createElement('canvas');
  canvas.width = atlas.width;
  canvas.height = atlas.height;
  const context = canvas.getContext('2d', { willReadFrequently: true });
  context.drawImage(atlas, 0, 0);
  const map = material.map.clone();
  map.source = new material.map.source.constructor(canvas);
  map.needsUpdate = true;
  kept = material.clone();
  kept.map = map;
  // Its coverage, for picking: a click on a quad's clear corner passes through it.
  kept.userData.coverage = { width: canvas.width, height: canvas.height, rgba: context.getImageData(0, 0, canvas.width, canvas.height).data };
  impostors.set(material.name, kept);
  return kept;
}

// The bytes a tile holds of its own (its trees' matrices, colours and rows), for the tile
// cache's bound: the meshes it draws are shared.
export function ownBytes(root) {
  let bytes = 0;
  root.traverse((o) => { if (o.isInstancedMesh) bytes += o.count * (64 + 12 + 400); });
  return bytes;
}

// Takes hold of `mesh` (an InstancedMesh of a loaded tile): reads its trees once.
export function prepare(mesh) {
  if (mesh.userData.sylva) return mesh.userData.sylva;
  const n = mesh.count;
  const ids = mesh.geometry.getAttribute('_FEATURE_ID_0');
  let meta = null;
  for (let o = mesh; o && !meta; o = o.parent) meta = o.userData.structuralMetadata || null;
  const rows = new Array(n);
  for (let i = 0; i < n; i++) rows[i] = ids && meta ? meta.getPropertyTableData(0, ids.getX(i)) : null;
  const state = {
    n,
    rows,
    // The tree's parts as one mesh, and each tree's bounding sphere by it (`combine`), on its
    // first part only.
    merged: null,
    spheres: null,
    // The impostor's own material, where the tree is drawn as one (`combine`); else the trees'.
    material: null,
    matrices: mesh.instanceMatrix.array.slice(),
    colours: new Float32Array(3 * n).fill(1),
    // Each tree's species colour (`setSpeciesColours`), worked out when first drawn as a
    // marker under that palette.
    tints: null,
    tintVersion: -1,
  };
  mesh.userData.sylva = state;
  return state;
}

// The state of a coarse tile's points (`LEFT_OUT`), as `prepare` keeps a tile mesh's: each
// point's species as its row (so `paint` and the species colours treat it as a tree; a filter
// on DBH or benefits dims it, its figures not being in the tile), where it stands, its colour.
// The left-out trees' dots are smaller than a marker: a dense city's 100,000 of them draw its
// streets as fine lines, where dots a marker's size ran together (and turned the software
// view at 7 frames a second, filling each pixel several times).
const LEFT_OUT_SIZE = 3;
const LEFT_OUT_PER_PIXEL = 0.12;
const LEFT_OUT_MATERIAL = new T.PointsMaterial({ size: LEFT_OUT_SIZE, sizeAttenuation: false, vertexColors: true });

export function pointsOf(points) {
  if (points.userData.sylva) return points.userData.sylva;
  const g = points.geometry, at = g.getAttribute('position'), cls = g.getAttribute('_class');
  const classes = points.userData.classes || [];
  const rows = new Array(at.count);
  const named = classes.map((species) => ({ species }));
  for (let i = 0; i < at.count; i++) rows[i] = named[cls ? cls.getX(i) : 0] ?? null;
  const state = {
    n: at.count,
    rows,
    colours: new Float32Array(3 * at.count).fill(1),
    tints: null,
    tintVersion: -1,
    // The palette version its colours were last painted under, and whether a filter changed
    // them since (`Batches.leftOut`).
    paintedAt: -1,
    dirty: true,
  };
  g.setAttribute('color', new T.BufferAttribute(new Float32Array(3 * at.count), 3));
  points.material = LEFT_OUT_MATERIAL;
  points.userData.sylva = state;
  return state;
}

// Each tree's bounding sphere in the mesh's frame: `sphere`, moved and scaled by the tree's
// matrix.
function spheresOf(mesh, sphere) {
  const spheres = new Float32Array(4 * mesh.count);
  const m = new T.Matrix4(), c = new T.Vector3();
  for (let i = 0; i < mesh.count; i++) {
    mesh.getMatrixAt(i, m);
    c.copy(sphere.center).applyMatrix4(m);
    spheres.set([c.x, c.y, c.z, sphere.radius * m.getMaxScaleOnAxis()], 4 * i);
  }
  return spheres;
}

// Each tree's species colour under the current palette, times its colour under the filters.
function tintsOf(s) {
  if (s.tintVersion !== paletteVersion) {
    s.tints = new Float32Array(3 * s.n);
    for (let i = 0; i < s.n; i++) {
      const c = palette.get(s.rows[i]?.species) || [other.r, other.g, other.b];
      s.tints.set(c, 3 * i);
    }
    s.tintVersion = paletteVersion;
  }
  return s.tints;
}

// Whether a ray that hit a batch mesh of `material` at texture point `uv` hit the tree: an
// impostor's quad is clear where its atlas is (glTF's texture points run from the picture's
// top left), every other mesh is solid.
export function solidAt(material, uv) {
  const c = material.userData.coverage;
  if (!c || !uv) return true;
  const x = Math.min(c.width - 1, Math.max(0, Math.floor(uv.x * c.width)));
  const y = Math.min(c.height - 1, Math.max(0, Math.floor(uv.y * c.height)));
  return c.rgba[4 * (y * c.width + x) + 3] >= 128;
}

// The row of tree `i` of the tile mesh `mesh`.
export function rowOf(mesh, i) {
  return mesh.userData.sylva?.rows[i] ?? null;
}

// Every tree of `mesh`, if it stands for its trees (`combine`): [row, lit].
export function* trees(mesh) {
  const s = mesh.userData.sylva;
  if (!s?.merged) return;
  for (let i = 0; i < s.n; i++) yield [s.rows[i], s.colours[3 * i] > 0.5];
}

// Colours every tree of `mesh`: full where `keep(row)`, `dim` elsewhere; `null` keeps all.
export function paint(mesh, keep, dim) {
  const s = mesh.isPoints ? pointsOf(mesh) : prepare(mesh);
  s.dirty = true;
  for (let i = 0; i < s.n; i++) {
    const lit = !keep || (s.rows[i] && keep(s.rows[i]));
    s.colours.set(lit ? [1, 1, 1] : [dim.r, dim.g, dim.b], 3 * i);
  }
}

// The trees in view, one instanced mesh per grown tree of the tiles shown.
export class Batches {
  constructor(scene) {
    this.group = new T.Group();
    this.group.name = 'trees in view';
    scene.add(this.group);
    this.byKey = new Map();
    this.markers = new Markers();
    this.group.add(this.markers.points);
  }

  // Gathers the trees of every tile mesh under `root` that the camera sees (`view`: its
  // projection times its inverse world matrix), each as its mesh or, where its crown would be
  // narrower than MARKER_PIXELS, as a marker. `eye`: the camera's position in the world, and
  // the drawn pixels one metre spans one metre in front of it.
  fill(root, view, eye) {
    for (const b of this.byKey.values()) b.n = 0;
    const markers = this.markers;
    markers.n = 0;
    this.leftOutShown = 0;
    // Crown radius r at distance d is drawn r * eye.pixels / d pixels across its half.
    const smallest = MARKER_PIXELS / 2 / eye.pixels;
    root.updateMatrixWorld();
    root.traverse((o) => {
      if (o.isPoints && o.name.startsWith(LEFT_OUT)) {
        this.leftOut(o, eye);
        return;
      }
      if (!o.isInstancedMesh) return;
      // The tile's own mesh is data from here on: the batches draw its trees.
      o.visible = false;
      const s = prepare(o);
      if (!s.merged) return;
      toLocal.multiplyMatrices(view, o.matrixWorld);
      frustum.setFromProjectionMatrix(toLocal);
      const planes = frustum.planes;
      // The eye in the tile mesh's own frame (a turn and a shift of the world's: distances
      // are the same in both).
      eyeHere.copy(eye.position).applyMatrix4(fromWorld.copy(o.matrixWorld).invert());
      const [ex, ey, ez] = [eyeHere.x, eyeHere.y, eyeHere.z];
      let b = null, tints = null;
      for (let i = 0; i < s.n; i++) {
        const x = s.spheres[4 * i], y = s.spheres[4 * i + 1], z = s.spheres[4 * i + 2], r = s.spheres[4 * i + 3];
        let inside = true;
        for (let p = 0; p < 6 && inside; p++) {
          const q = planes[p];
          inside = q.normal.x * x + q.normal.y * y + q.normal.z * z + q.constant >= -r;
        }
        if (!inside) continue;
        // The sphere's radius is about the crown's (the tree's height bounds it).
        const dx = x - ex, dy = y - ey, dz = z - ez;
        if (r * r < smallest * smallest * (dx * dx + dy * dy + dz * dz)) {
          tints ??= tintsOf(s);
          centre.set(x, y, z).applyMatrix4(o.matrixWorld);
          markers.add(centre, tints, s.colours, i, [o, i]);
          continue;
        }
        b ??= this.batch(s.merged, s.material ?? TREE_MATERIAL);
        if (b.n === b.mesh.instanceMatrix.count) this.grow(b);
        world.fromArray(s.matrices, 16 * i).premultiply(o.matrixWorld);
        world.toArray(b.mesh.instanceMatrix.array, 16 * b.n);
        b.mesh.instanceColor.array.set(s.colours.subarray(3 * i, 3 * i + 3), 3 * b.n);
        b.refs[b.n] = [o, i];
        b.n++;
      }
    });
    let calls = 0;
    for (const b of this.byKey.values()) {
      b.mesh.count = b.n;
      b.mesh.visible = b.n > 0;
      b.refs.length = b.n;
      // Only the trees gathered go to the GPU, not the batch's whole capacity.
      for (const [a, size] of [[b.mesh.instanceMatrix, 16], [b.mesh.instanceColor, 3]]) {
        a.clearUpdateRanges();
        a.addUpdateRange(0, size * b.n);
        a.needsUpdate = true;
      }
      b.mesh.boundingSphere = null;
      if (b.n) calls++;
    }
    if (markers.finish()) calls++;
    return calls;
  }

  // A coarse tile's points (the trees it leaves out of its meshes: a parent draws its
  // tallest 1,000) drawn as markers, so a dense city seen whole shows every tree, and its
  // streets with them. They stand still in the tile, so the tile's own points are drawn (one
  // draw a tile) rather than gathered each frame (96,000 of them turned the view at 5 frames a
  // second). They have no row in the tile, so no card: a click finds the nearest marker that
  // has one, and zooming in brings the finer tiles that draw them.
  leftOut(o, eye) {
    const s = pointsOf(o);
    // The tile holds its points shuffled, so a first share of them is an even sample: as many
    // as LEFT_OUT_PER_PIXEL a drawn pixel of the tile's disc on the screen. A software view of
    // the 100,000-tree demo, whole, turned at 9 frames a second with all 96,000 dots, at 11
    // with 30,000 (0.25 a pixel), at 14.7 with 15,000 (0.12), its streets still showing.
    const sphere = o.geometry.boundingSphere || (o.geometry.computeBoundingSphere(), o.geometry.boundingSphere);
    centre.copy(sphere.center).applyMatrix4(o.matrixWorld);
    const across = (sphere.radius * eye.pixels) / Math.max(1e-3, centre.distanceTo(eye.position));
    const shown = Math.min(s.n, Math.ceil(Math.PI * across * across * LEFT_OUT_PER_PIXEL));
    o.geometry.setDrawRange(0, shown);
    const tints = tintsOf(s);
    if (s.paintedAt !== s.tintVersion || s.dirty) {
      const colour = o.geometry.getAttribute('color').array;
      for (let k = 0; k < 3 * s.n; k++) colour[k] = tints[k] * s.colours[k];
      o.geometry.getAttribute('color').needsUpdate = true;
      s.paintedAt = s.tintVersion;
      s.dirty = false;
    }
    o.visible = true;
    this.leftOutShown += shown;
  }

  batch(geometry, material) {
    const key = `${geometry.uuid}|${material.uuid}`;
    let b = this.byKey.get(key);
    if (!b) {
      b = { mesh: this.make(geometry, material, 64), refs: [], n: 0 };
      this.byKey.set(key, b);
      this.group.add(b.mesh);
    }
    return b;
  }

  make(geometry, material, capacity) {
    const mesh = new T.InstancedMesh(geometry, material, capacity);
    mesh.instanceColor = new T.InstancedBufferAttribute(new Float32Array(3 * capacity).fill(1), 3);
    // Culled tree by tree above.
    mesh.frustumCulled = false;
    return mesh;
  }

  grow(b) {
    const old = b.mesh;
    const mesh = this.make(old.geometry, old.material, 2 * old.instanceMatrix.count);
    mesh.instanceMatrix.array.set(old.instanceMatrix.array);
    mesh.instanceColor.array.set(old.instanceColor.array);
    this.group.remove(old);
    old.dispose();
    this.group.add(mesh);
    b.mesh = mesh;
  }

  // Drops the batches of meshes no tile shows any more (after a tileset is swapped).
  clear() {
    for (const b of this.byKey.values()) { this.group.remove(b.mesh); b.mesh.dispose(); }
    this.byKey.clear();
  }

  // The batch meshes, for picking.
  meshes() {
    return [...this.byKey.values()].filter((b) => b.n > 0).map((b) => b.mesh);
  }

  // The tile mesh and tree of the marker drawn nearest a point of the screen (`x`, `y`: -1
  // to 1 across the drawing) within `within` of it (the same units), with `camera`.
  markerAt(camera, x, y, within) {
    const m = this.markers, p = new T.Vector3();
    let best = null, bestD = within * within;
    for (let i = 0; i < m.n; i++) {
      p.fromArray(m.position, 3 * i).project(camera);
      if (p.z > 1) continue;
      const d = (p.x - x) ** 2 + (p.y - y) ** 2;
      if (d < bestD && m.refs[i]) { bestD = d; best = m.refs[i]; }
    }
    return best;
  }

  // The tile mesh and tree drawn as instance `id` of batch mesh `mesh`.
  ref(mesh, id) {
    for (const b of this.byKey.values()) if (b.mesh === mesh) return b.refs[id] ?? null;
    return null;
  }
}

// Trees too small to see, as points a few pixels wide in their species' colour: one draw
// for all of them, a vertex each.
class Markers {
  constructor() {
    this.n = 0;
    this.refs = [];
    this.material = new T.PointsMaterial({ size: MARKER_SIZE, sizeAttenuation: false, vertexColors: true });
    this.points = new T.Points(new T.BufferGeometry(), this.material);
    this.points.name = 'markers';
    // Only the trees in view are gathered.
    this.points.frustumCulled = false;
    this.make(1024);
  }

  make(capacity) {
    const g = new T.BufferGeometry();
    const position = new Float32Array(3 * capacity), colour = new Float32Array(3 * capacity);
    if (this.position) { position.set(this.position); colour.set(this.colour); }
    this.position = position;
    this.colour = colour;
    g.setAttribute('position', new T.BufferAttribute(position, 3));
    g.setAttribute('color', new T.BufferAttribute(colour, 3));
    this.points.geometry.dispose();
    this.points.geometry = g;
  }

  // Tree `i` at `at` (world), its species colour from `tints` times its filter colour.
  add(at, tints, colours, i, ref) {
    if (3 * (this.n + 1) > this.position.length) this.make(2 * this.position.length / 3);
    const k = 3 * this.n;
    this.position[k] = at.x; this.position[k + 1] = at.y; this.position[k + 2] = at.z;
    for (let c = 0; c < 3; c++) this.colour[k + c] = tints[3 * i + c] * colours[3 * i + c];
    this.refs[this.n] = ref;
    this.n++;
  }

  // Sends this frame's markers to the GPU; whether there are any.
  finish() {
    const g = this.points.geometry;
    g.setDrawRange(0, this.n);
    this.refs.length = this.n;
    for (const name of ['position', 'color']) {
      const a = g.getAttribute(name);
      a.clearUpdateRanges();
      a.addUpdateRange(0, 3 * this.n);
      a.needsUpdate = true;
    }
    this.points.visible = this.n > 0;
    return this.n > 0;
  }
}
