// The city view's ground: a plain under the trees' extent, outlined, and an XYZ basemap over it
// where the server was started with one (`sylva serve --basemap`).

import * as T from '/vendor/city.min.js';

// The trees' extent in page metres, from the root tile's box (centre, then three half axes, in
// the tileset's east-north-up frame).
export function extentOf(box) {
  const [cx, cy, , ax, , , , by] = box;
  return { x0: cx - Math.abs(ax), x1: cx + Math.abs(ax), n0: cy - Math.abs(by), n1: cy + Math.abs(by) };
}

// The plain ground under a city's trees, its extent outlined, and the basemap over it where
// the server was given one and the city knows where it lies.
export function drawGround(ground, e, basemap, origin, probe, redraw) {
  ground.clear();
  const w = e.x1 - e.x0, d = e.n1 - e.n0, margin = 0.15 * Math.max(w, d) + 50;
  const plane = new T.Mesh(new T.PlaneGeometry(w + 2 * margin, d + 2 * margin),
    new T.MeshLambertMaterial({ color: '#b9c4a6' }));
  plane.rotation.x = -Math.PI / 2;
  plane.position.set((e.x0 + e.x1) / 2, -0.05, -(e.n0 + e.n1) / 2);
  ground.add(plane);
  const g = new T.BufferGeometry();
  g.setAttribute('position', new T.Float32BufferAttribute(
    [e.x0, 0.05, -e.n0, e.x1, 0.05, -e.n0, e.x1, 0.05, -e.n1, e.x0, 0.05, -e.n1], 3));
  ground.add(new T.LineLoop(g, new T.LineBasicMaterial({ color: '#6a5a3a' })));
  if (basemap && origin) drawBasemap({ ground, e, margin, plain: plane, basemap, origin, probe, redraw });
}

// An XYZ (Web Mercator) map under the trees: the tiles of one zoom level over the extent,
// placed by their corners' longitude and latitude in the city's local metres (metres per degree
// on the WGS84 ellipsoid at the city's latitude: within a metre over a city's width).
function drawBasemap({ ground, e, margin, plain, basemap, origin, probe, redraw }) {
  const { longitude: lon0, latitude: lat0 } = origin;
  const phi = lat0 * Math.PI / 180;
  const mLat = 111132.92 - 559.82 * Math.cos(2 * phi) + 1.175 * Math.cos(4 * phi);
  const mLon = 111412.84 * Math.cos(phi) - 93.5 * Math.cos(3 * phi);
  const lonOf = (x) => lon0 + x / mLon, latOf = (n) => lat0 + n / mLat;
  const span = Math.max(e.x1 - e.x0, e.n1 - e.n0) + 2 * margin;
  const z = Math.max(1, Math.min(19, Math.round(Math.log2(40075016 * Math.cos(phi) / (span / 6)))));
  const n = 2 ** z;
  const tx = (lon) => Math.floor(((lon + 180) / 360) * n);
  const ty = (lat) => {
    const r = lat * Math.PI / 180;
    return Math.floor(((1 - Math.log(Math.tan(r) + 1 / Math.cos(r)) / Math.PI) / 2) * n);
  };
  const lonAt = (x) => (x / n) * 360 - 180;
  const latAt = (y) => Math.atan(Math.sinh(Math.PI * (1 - (2 * y) / n))) * 180 / Math.PI;
  const [xa, xb] = [tx(lonOf(e.x0 - margin)), tx(lonOf(e.x1 + margin))];
  const [ya, yb] = [ty(latOf(e.n1 + margin)), ty(latOf(e.n0 - margin))];
  const count = (xb - xa + 1) * (yb - ya + 1);
  if (count > 100) return;
  let drawn = 0;
  const loader = new T.TextureLoader();
  loader.setCrossOrigin('anonymous');
  probe.basemapTiles = [];
  for (let x = xa; x <= xb; x++) for (let y = ya; y <= yb; y++) {
    const url = basemap.replace('{z}', z).replace('{x}', x).replace('{y}', y);
    probe.basemapTiles.push(url);
    loader.load(url, (texture) => {
      texture.colorSpace = T.SRGBColorSpace;
      // Seen from above, a map tile is drawn near its own size: no mipmaps, which a CPU
      // drawing WebGL pays for in every pixel (1006: three.js's LinearFilter).
      texture.generateMipmaps = false;
      texture.minFilter = 1006;
      const west = (lonAt(x) - lon0) * mLon, east = (lonAt(x + 1) - lon0) * mLon;
      const north = (latAt(y) - lat0) * mLat, south = (latAt(y + 1) - lat0) * mLat;
      const tile = new T.Mesh(new T.PlaneGeometry(east - west, north - south),
        new T.MeshBasicMaterial({ map: texture }));
      tile.rotation.x = -Math.PI / 2;
      tile.position.set((west + east) / 2, -0.02, -(north + south) / 2);
      ground.add(tile);
      probe.basemapDrawn = ++drawn;
      // The map's tiles cover the plain ground and its margin: once all are in, it is not
      // drawn beneath them.
      if (drawn === count) plain.visible = false;
      redraw();
    }, undefined, () => { probe.basemapFailed = (probe.basemapFailed || 0) + 1; });
  }
}
