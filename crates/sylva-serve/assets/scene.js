// The 3-D street: grown trees side by side on the chosen site, with the façade, wires, street
// lights, a 1.8 m person for scale, and the sun at noon on midsummer's day casting shadows.
//
// Site frame (Sylva's, metres): x along the street, y across it (negative: the roadway;
// positive: the buildings), z up, each tree's trunk at its own x. three.js is Y up, so a site
// point (x, y, z) is drawn at (x, z, -y), as Sylva's GLB files turn it.

import * as THREE from '/vendor/three.min.js';
import { softwareGl } from '/gl.js';

const at = (x, y, z) => new THREE.Vector3(x, z, -y);

export class Street {
  constructor(canvas) {
    this.canvas = canvas;
    // Multisampling multiplies what a browser drawing WebGL on its CPU must fill (a frame of
    // two 50-year trees: 171 ms with it, 99 ms without, SwiftShader on two cores), so only a
    // graphics card gets it.
    this.software = softwareGl();
    this.renderer = new THREE.WebGLRenderer({ canvas, antialias: !this.software, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
    this.renderer.shadowMap.enabled = true;
    // Soft shadows look up the shadow map several times a pixel. Without a GPU that doubles
    // the cost of a frame of the coarsest trees (a street and two 50-year leaf shells: 34-38
    // ms soft, 21-27 ms hard, SwiftShader on two cores), so there the shadows are hard-edged.
    // The map is drawn anew with every change of trees, and a smaller one there saves another
    // 6 ms a change (texels of about 6 cm over a street of two trees).
    this.renderer.shadowMap.type = this.software ? THREE.BasicShadowMap : THREE.PCFSoftShadowMap;
    // The sun and everything that casts a shadow stand still while the view turns, so the
    // shadow map is drawn again only when the street or the trees change (see `changed`).
    this.renderer.shadowMap.autoUpdate = false;
    this.renderer.outputColorSpace = THREE.SRGBColorSpace;
    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color(0xcfe0ee);
    this.camera = new THREE.PerspectiveCamera(40, 1, 0.1, 2000);
    this.controls = new THREE.OrbitControls(this.camera, canvas);
    this.controls.enableDamping = false;
    this.controls.maxPolarAngle = Math.PI * 0.495;
    this.controls.addEventListener('change', () => this.draw());
    this.scene.add(new THREE.HemisphereLight(0xdfeaf5, 0x5a5346, 1.1));
    this.sun = new THREE.DirectionalLight(0xffffff, 2.2);
    this.sun.castShadow = true;
    this.sun.shadow.mapSize.setScalar(this.software ? 1024 : 2048);
    this.sun.shadow.bias = -0.0005;
    this.sun.shadow.normalBias = 0.02;
    this.scene.add(this.sun, this.sun.target);
    this.site = new THREE.Group();
    this.trees = new THREE.Group();
    this.scene.add(this.site, this.trees);
    this.slots = [];
    this.framed = null;
    this.changed = true;
    this.pendingMs = 0;
    new ResizeObserver(() => this.resize()).observe(canvas);
    this.resize();
  }

  resize() {
    const w = this.canvas.clientWidth || 640;
    const h = this.canvas.clientHeight || 480;
    this.renderer.setSize(w, h, false);
    viewportHeight.value = this.renderer.getDrawingBufferSize(new THREE.Vector2()).y;
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    this.draw();
  }

  draw() {
    if (this.changed) {
      this.renderer.shadowMap.needsUpdate = true;
      this.changed = false;
    }
    this.renderer.render(this.scene, this.camera);
    if (this.onDraw) this.onDraw();
  }

  // Draws and waits for the frame to be finished (reading one pixel back makes the browser
  // finish it): how long this computer takes to draw the street, ms. What the browser was
  // still drawing before (the page's charts, drawn in the same turn as a new age) is finished
  // first, so that the time is the frame's own; that wait is kept in `pendingMs`.
  timedDraw() {
    const gl = this.renderer.getContext();
    const pixel = new Uint8Array(4);
    const t0 = performance.now();
    gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, pixel);
    const t1 = performance.now();
    this.draw();
    gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, pixel);
    this.pendingMs = t1 - t0;
    return performance.now() - t1;
  }

  // Lays out `count` tree slots `spacing` metres apart on `site`, with the sun of `latitude`
  // at noon on 21 June. Rebuilt only when one of these changes.
  setStreet(site, count, spacing, latitude, tallest) {
    const key = JSON.stringify([site, count, spacing, latitude, tallest]);
    if (key === this.streetKey) return;
    this.streetKey = key;
    this.lastSite = site;
    this.site.clear();
    this.changed = true;
    this.slots = [];
    for (let i = 0; i < count; i++) this.slots.push((i - (count - 1) / 2) * spacing);
    const half = (count * spacing) / 2 + 8;
    const s = site.street;
    const wall = site.facade ? site.facade.setback : Math.max(s.sidewalk[1] + 4, 8);
    const flat = (color) => new THREE.MeshLambertMaterial({ color });
    const slab = (y0, y1, color, z = 0) => {
      const g = new THREE.PlaneGeometry(2 * half, Math.abs(y1 - y0));
      g.rotateX(-Math.PI / 2);
      const m = new THREE.Mesh(g, flat(color));
      m.position.copy(at(0, (y0 + y1) / 2, z));
      m.receiveShadow = true;
      this.site.add(m);
    };
    // Roadway, planting strip, sidewalk, and paving up to the wall (not green: leaves are the
    // only green in the picture, which the browser test counts).
    slab(s.curb - 14, s.curb, 0x55585c);
    slab(s.curb, s.sidewalk[0], 0x7b6a4e, 0.01);
    slab(s.sidewalk[0], s.sidewalk[1], 0xc9c6bd, 0.02);
    slab(s.sidewalk[1], wall + 30, 0xb9b2a0, 0.0);
    // Lane marking.
    slab(s.curb - 7.1, s.curb - 6.95, 0xf2f2f2, 0.015);
    const box = (w, h, d, color, x, y, z) => {
      const m = new THREE.Mesh(new THREE.BoxGeometry(w, h, d), flat(color));
      m.position.copy(at(x, y, z));
      m.castShadow = m.receiveShadow = true;
      this.site.add(m);
      return m;
    };
    if (site.facade) {
      const f = site.facade;
      box(2 * half, f.height, 0.4, 0xd8cbb3, 0, f.setback + 0.2, f.height / 2);
      // Windows: a band of glass per storey, as tall as the wall's share of glass needs (one
      // box a storey keeps the draw calls few for a browser drawing on its CPU).
      const storeys = Math.max(1, Math.floor(f.height / 3));
      for (let k = 0; k < storeys; k++) {
        box(2 * half, Math.min(2.6, 3 * f.window_share), 0.05, 0x3d4c5c, 0, f.setback - 0.01, k * 3 + 1.6);
      }
    }
    for (const slot of this.slots) {
      for (const a of site.awning || []) {
        box(a.along[1] - a.along[0], a.top - a.bottom, a.reach, 0x9b3b32,
          slot + (a.along[0] + a.along[1]) / 2, wall - a.reach / 2, (a.top + a.bottom) / 2);
      }
      for (const a of site.sign || []) {
        box(a.along[1] - a.along[0], a.top - a.bottom, 0.1, 0x2d5d8a,
          slot + (a.along[0] + a.along[1]) / 2, wall - a.reach, (a.top + a.bottom) / 2);
      }
      for (const l of site.light || []) {
        box(0.16, l.height, 0.16, 0x4a4a4a, slot + l.x, l.y, l.height / 2);
        box(0.8, 0.15, 0.35, 0xeeeeaa, slot + l.x, l.y, l.height);
      }
    }
    for (const w of site.wire || []) {
      const g = new THREE.CylinderGeometry(0.02, 0.02, 2 * half, 6);
      g.rotateZ(Math.PI / 2);
      const m = new THREE.Mesh(g, flat(0x111111));
      m.position.copy(at(0, w.offset, w.height));
      this.site.add(m);
      // Poles between the trees (and at both ends of the row), never through a crown.
      const poles = [this.slots[0] - spacing / 2, ...this.slots.map((x) => x + spacing / 2)];
      for (const x of poles) box(0.3, w.height + 0.5, 0.3, 0x6b4f33, x, w.offset, (w.height + 0.5) / 2);
    }
    // The person stands on the sidewalk beside the first tree, where the eye compares them.
    this.site.add(person(at(this.slots[0] + 2.2, (s.sidewalk[0] + s.sidewalk[1]) / 2, 0)));
    // The sun at solar noon on 21 June: elevation 90° - latitude + 23.44°, from the south.
    // Which way is south in the site: the façade faces `faces` degrees from north, and the
    // street (-y) lies in front of it.
    const faces = site.facade ? site.facade.faces : 180;
    const elevation = (90 - latitude + 23.44) * Math.PI / 180;
    const d = (180 - faces) * Math.PI / 180;
    const south = new THREE.Vector2(-Math.sin(d), -Math.cos(d));
    const far = 80;
    this.sun.position.copy(at(south.x * Math.cos(elevation) * far, south.y * Math.cos(elevation) * far,
      Math.sin(elevation) * far));
    this.sun.target.position.set(0, 0, 0);
    const cam = this.sun.shadow.camera;
    const r = Math.max(half, tallest) + 4;
    cam.left = -r; cam.right = r; cam.top = r; cam.bottom = -r; cam.near = 1; cam.far = 2 * far + r;
    cam.updateProjectionMatrix();
    if (this.framed !== key) this.frame(half, tallest);
  }

  // A view from across the road that takes in every tree at its tallest and, whatever the
  // canvas's shape, the widest crowns of the outermost trees (`half` is the row's half-length
  // plus 8 m of street; the trees themselves reach `half - 8`).
  frame(half, tallest) {
    this.framed = this.streetKey;
    const target = new THREE.Vector3(0, tallest * 0.45, 0);
    const tan = Math.tan((this.camera.fov * Math.PI) / 360);
    const wide = (half - 7) / (tan * Math.max(0.3, this.camera.aspect));
    const distance = Math.max(wide * 1.15, tallest * 2.2, 12);
    this.camera.position.set(0, tallest * 0.45 + distance * 0.18, distance);
    this.controls.target.copy(target);
    this.controls.update();
  }

  // Draws a frame with a stand-in bark, leaf and shell mesh, so that every shader the trees
  // need is compiled while their files are still on the way (a browser drawing WebGL on its
  // CPU takes a second over it).
  warm() {
    const bark = new THREE.Mesh(new THREE.BoxGeometry(0.1, 0.1, 0.1), material(0xffffff, false, THREE.FrontSide));
    // Stems that carry their radius, widened where thinner than a pixel.
    const stemBox = new THREE.BoxGeometry(0.1, 0.1, 0.1);
    stemBox.setAttribute('_radius', new THREE.BufferAttribute(new Float32Array(stemBox.attributes.position.count).fill(0.05), 1));
    const stems = new THREE.Mesh(stemBox, material(0xffffff, false, THREE.FrontSide, true));
    const leafBox = new THREE.BoxGeometry(0.1, 0.1, 0.1);
    const grey = new Float32Array(leafBox.attributes.position.count * 3).fill(1);
    leafBox.setAttribute('color', new THREE.BufferAttribute(grey, 3));
    const leaves = new THREE.Mesh(leafBox, material(0xffffff, true, THREE.DoubleSide));
    // The coarsest level's leaf shell: shaded like leaves, but one-sided.
    const shell = new THREE.Mesh(leafBox, material(0xffffff, true, THREE.FrontSide));
    for (const m of [bark, stems, leaves, shell]) { m.castShadow = m.receiveShadow = true; m.position.y = -5; }
    this.trees.add(bark, stems, leaves, shell);
    this.changed = true;
    const ms = this.timedDraw();
    this.trees.clear();
    this.changed = true;
    return ms;
  }

  // Puts `scenes[i]` (a glTF scene, or null) in slot i, casting and taking shadows.
  setTrees(scenes) {
    this.trees.clear();
    this.changed = true;
    scenes.forEach((s, i) => {
      if (!s) return;
      s.position.x = this.slots[i] ?? 0;
      // A leaf shell takes no shadow: its leaves' own light is drawn on it already, and a hard
      // shadow map draws stripes on a surface lit at a grazing angle.
      s.traverse((o) => {
        if (o.isMesh) { o.castShadow = true; o.receiveShadow = o.material.name !== 'leaf shell'; }
      });
      lambert(s);
      this.trees.add(s);
    });
    return this.timedDraw();
  }

  // Triangles of the trees shown.
  triangles() {
    let n = 0;
    this.trees.traverse((o) => { if (o.isMesh) n += (o.geometry.index?.count ?? 0) / 3; });
    return n;
  }

  // Screen position of a site point, for labels.
  project(x, y, z) {
    const p = at(x, y, z).project(this.camera);
    return [(p.x + 1) / 2 * this.canvas.clientWidth, (1 - p.y) / 2 * this.canvas.clientHeight, p.z < 1];
  }
}

// Diffuse materials shared by every tree, one per colour, vertex colours and sidedness: glTF
// files load as physically based materials, whose shaders a browser without a GPU compiles
// and fills several times slower, and a tree's bark and leaves are matte anyway.
const materials = new Map();
function material(color, vertexColors, side, thin = false) {
  const c = new THREE.Color(color);
  const key = `${c.getHexString()}|${vertexColors}|${side}|${thin}`;
  if (!materials.has(key)) {
    // Stems that may be thinner than a pixel are blended over what lies behind them, after
    // every opaque thing is drawn; they still write depth, so a trunk hides the twigs behind it.
    const m = new THREE.MeshLambertMaterial({ color: c, vertexColors, side, transparent: thin });
    if (thin) widenThin(m);
    materials.set(key, m);
  }
  return materials.get(key);
}

function lambert(root) {
  root.traverse((o) => {
    if (!o.isMesh || o.material.isMeshLambertMaterial) return;
    const m = o.material;
    o.material = material(m.color, !!m.vertexColors, m.side, !!o.geometry.attributes._radius);
  });
}

// The drawing buffer's height in pixels, shared by every material that widens thin stems.
const viewportHeight = { value: 1 };

// Stems thinner than a pixel, as the forest renderer draws far stems: each vertex of a stem
// whose radius (the GLB's _RADIUS) is under half a pixel at its distance moves out along its
// normal to half a pixel, so the stem is drawn one pixel wide, with the opacity of the share of
// that pixel its true width covers (radius over half a pixel). Without this a twig of 4 mm seen
// from 30 m either misses a pixel's centre or fills the pixel: drawn as broken dots without
// multisampling, and never as the faint line it is.
function widenThin(m) {
  m.onBeforeCompile = (shader) => {
    shader.uniforms.sylvaViewportHeight = viewportHeight;
    shader.vertexShader = shader.vertexShader
      .replace('#include <common>', `#include <common>
attribute float _radius;
uniform float sylvaViewportHeight;
varying float vSylvaCover;`)
      .replace('#include <begin_vertex>', `#include <begin_vertex>
{
  // A pixel's height at this vertex's distance: projectionMatrix[1][1] is 1 / tan(fov / 2).
  float depth = -(modelViewMatrix * vec4(transformed, 1.0)).z;
  float half_pixel = depth / (projectionMatrix[1][1] * sylvaViewportHeight);
  vSylvaCover = 1.0;
  if (_radius < half_pixel) {
    transformed += normalize(objectNormal) * (half_pixel - _radius);
    vSylvaCover = _radius / half_pixel;
  }
}`);
    shader.fragmentShader = shader.fragmentShader
      .replace('#include <common>', `#include <common>
varying float vSylvaCover;`)
      .replace('#include <color_fragment>', `#include <color_fragment>
diffuseColor.a *= vSylvaCover;`);
  };
  m.customProgramCacheKey = () => 'sylva-thin-stems';
}

// A 1.8 m person: legs, body, arms and head in plain shapes.
function person(base) {
  const g = new THREE.Group();
  const skin = new THREE.MeshLambertMaterial({ color: 0xc99c7a });
  const cloth = new THREE.MeshLambertMaterial({ color: 0x33506e });
  const part = (geometry, material, y) => {
    const m = new THREE.Mesh(geometry, material);
    m.position.y = y;
    m.castShadow = true;
    g.add(m);
    return m;
  };
  for (const side of [-0.1, 0.1]) {
    part(new THREE.CylinderGeometry(0.07, 0.06, 0.85, 8), cloth, 0.425).position.x = side;
    part(new THREE.CylinderGeometry(0.045, 0.04, 0.62, 8), cloth, 1.15).position.x = side * 2.4;
  }
  part(new THREE.CylinderGeometry(0.17, 0.15, 0.65, 10), cloth, 1.2);
  part(new THREE.SphereGeometry(0.11, 16, 12), skin, 1.69);
  g.position.copy(base);
  return g;
}
