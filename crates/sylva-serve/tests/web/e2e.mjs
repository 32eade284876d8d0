// End to end in a real browser: starts `sylva serve`, opens the page in the system's Chromium
// (headless, through playwright-core; no browser is downloaded), picks two species by typing
// their names, drags the age slider and sets ages from 5 to 50, and checks from screenshots
// that two trees and the charts are drawn. Prints the timings against the issue's targets
// (page load to the first tree drawn <= 2 s, a new age drawn <= 300 ms after the slider
// stops, a frame of two 50-year trees <= 100 ms), and fails only past five times a target: a shared CI machine without a GPU draws
// WebGL on its CPU (SwiftShader), and the figures to quote are the printed ones.
//
//   node e2e.mjs [path/to/sylva] [folder for the screenshots]

import { chromium } from 'playwright-core';
import { writeFileSync, mkdirSync } from 'node:fs';
import { startServer, waitUntil, check } from './common.mjs';

const bin = process.argv[2] || new URL('../../../../target/debug/sylva', import.meta.url).pathname;
const shots = process.argv[3] || null;
if (shots) mkdirSync(shots, { recursive: true });

// As the workplace's probe starts Chromium: headless, no sandbox as root, nothing phoning
// home; WebGL drawn by SwiftShader where there is no GPU.
const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
  args: ['--no-sandbox', '--disable-quic', '--no-first-run', '--disable-background-networking',
    '--disable-component-update', '--disable-sync', '--use-angle=swiftshader',
    '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist'],
});
const server = await startServer(bin);
let failed = false;
try {
  const opened = await browser.newPage({ viewport: { width: 1600, height: 1000 } });
  watch(opened);

  // 1. The page as `sylva serve --open` shows it, opened the moment the server is up.
  await opened.goto(server.url);
  const first = await waitUntil('the first trees', () => opened.evaluate(() => window.sylva?.firstTreeMs), 60);
  console.log(`page load to the first trees drawn, server just started: ${first.toFixed(0)} ms`);
  // And once more in a new tab, with the default species grown.
  await waitUntil('the default species grown', async () => {
    const s = await (await fetch(`${server.url}api/status`)).json();
    return s.growths >= 2 && s.growing === 0;
  }, 120);
  await opened.close();
  const page = await browser.newPage({ viewport: { width: 1600, height: 1000 } });
  watch(page);
  await page.goto(server.url);
  const again = await waitUntil('the first trees', () => page.evaluate(() => window.sylva?.firstTreeMs), 60);
  console.log(`page load to the first trees drawn, trees grown: ${again.toFixed(0)} ms`);
  target('page load to the first trees drawn, server just started', first, 2000);
  target('page load to the first trees drawn, trees grown', again, 2000);

  // 2. Pick two species as a planner would: remove what is shown, type names, press Enter.
  while (await page.locator('#chosen .chip button').count() > 0) {
    await page.locator('#chosen .chip button').first().click();
  }
  for (const name of ['London plane', 'pistache']) {
    await page.fill('#search', name.slice(0, 6));
    await page.waitForSelector('#matches li');
    await page.fill('#search', name);
    await page.press('#search', 'Enter');
  }
  const chosen = await page.locator('#chosen .chip').allTextContents();
  check(chosen.length === 2 && /London/.test(chosen[0]) && /pistache/i.test(chosen[1]),
    `two species picked by name: ${chosen.join(', ')}`);
  await waitUntil('both growth tables', () => page.evaluate(() => window.sylva.tables >= 2), 120);

  // 3. Drag the slider with the mouse to the left end, then set ages 5 to 50 as a drag ends.
  const slider = await page.locator('#age').boundingBox();
  const [lo, hi] = await page.evaluate(() => [Number(age.min), Number(age.max)]);
  const xOf = (a) => slider.x + 8 + ((a - lo) / (hi - lo)) * (slider.width - 16);
  const drawsBefore = await page.evaluate(() => window.sylva.ageDraws.length);
  await page.mouse.move(xOf(20), slider.y + slider.height / 2);
  await page.mouse.down();
  for (let a = 19; a >= 5; a -= 2) await page.mouse.move(xOf(a), slider.y + slider.height / 2, { steps: 2 });
  await page.mouse.move(xOf(5), slider.y + slider.height / 2);
  await page.mouse.up();
  const dragged = await page.evaluate(() => Number(age.value));
  await waitUntil('the dragged age drawn', () => page.evaluate((n) => window.sylva.ageDraws.length > n &&
    window.sylva.shownAge === Number(age.value), drawsBefore), 30);
  console.log(`dragged the slider to ${dragged}`);
  const draws = [];
  for (const a of [5, 10, 20, 30, 40, 50]) {
    const n = await page.evaluate(() => window.sylva.ageDraws.length);
    await page.evaluate((a) => { age.value = a; age.dispatchEvent(new Event('input')); }, a);
    await waitUntil(`age ${a} drawn`, () => page.evaluate((n) => window.sylva.ageDraws.length > n, n), 30);
    const d = await page.evaluate(() => window.sylva.ageDraws.at(-1));
    draws.push(d);
    if (a === 5 || a === 50) await look(page, a);
  }
  // 4. The coarsest level (leaf shells) pinned, two 50-year trees: a frame as the view turns
  // (the shadow map stands still; the median of nine) and the first frame of the trees.
  const pinned = await browser.newPage({ viewport: { width: 1600, height: 1000 } });
  watch(pinned);
  await pinned.goto(`${server.url}?species=PLAC,PICH&age=50&detail=4`);
  await waitUntil('the pinned trees', () => pinned.evaluate(() => window.sylva?.firstTreeMs), 60);
  const shells = await pinned.evaluate(() => {
    const t = Array.from({ length: 9 }, () => window.sylvaStreet.timedDraw()).sort((a, b) => a - b);
    return { turning: t[4], first: window.sylva.frames[0][1], detail: window.sylva.detail,
      triangles: window.sylvaStreet.triangles() };
  });
  await pinned.close();
  check(shells.detail === 4, `the page keeps a pinned level: ${shells.detail}`);
  console.log(`two 50-year trees as leaf shells (${shells.triangles} triangles): a frame as the view turns ${shells.turning.toFixed(0)} ms, the first frame ${shells.first.toFixed(0)} ms`);
  // 5. Stems thinner than a pixel cover the share of it their width does: the bark alone of two
  // 30-year trees at the level a computer without a GPU draws (3), black on white, at the
  // canvas's resolution and at four times it. The twigs are drawn as partly covered pixels, and
  // the bark covers the same area at both resolutions (a twig widened to a pixel but drawn
  // opaque would cover several times its area at the coarser one).
  const thin = await browser.newPage({ viewport: { width: 1600, height: 1000 } });
  watch(thin);
  await thin.goto(`${server.url}?species=PLAC,PICH&age=30&detail=3`);
  await waitUntil('the 30-year trees', () => thin.evaluate(() => window.sylva?.firstTreeMs), 60);
  const stems = await thin.evaluate(thinStems);
  await thin.close();
  console.log(`bark of two 30-year trees: ${stems.partial.toFixed(2)} of its pixels partly covered; covered area ${stems.area[0].toFixed(0)} px at the canvas's resolution, ${stems.area[1].toFixed(0)} at four times it (in the canvas's pixels)`);
  check(stems.partial > 0.3, 'thin stems drawn as partly covered pixels');
  check(Math.abs(stems.area[0] / stems.area[1] - 1) < 0.2, 'the bark covers the same area at either resolution');

  // 6. The typical position is the site menu's first choice and what the page opens on; its
  // bars are i-Tree's categories.
  const menu = await page.evaluate(() => [...document.querySelectorAll('#site option')].map((o) => o.value));
  const note = await page.locator('#table .note').textContent();
  check(menu[0] === 'typical' && menu.length >= 2 && /typical position/i.test(note),
    `site menu ${menu.join(', ')}; table says: ${note}`);
  // 7. Four trees in a row are framed whole: the outermost crowns' edges, at the ground and
  // at the tallest, fall inside the canvas at the default camera.
  const framed = await page.evaluate(() => {
    const s = window.sylvaStreet;
    const site = s.lastSite;
    const spacing = 14, tallest = 22;
    s.streetKey = null;
    s.framed = null;
    s.setStreet(site, 4, spacing, 37.6, tallest);
    const edge = 2 * spacing;
    const seen = [[-edge, 0], [edge, 0], [-edge, tallest], [edge, tallest]].map(([x, z]) => {
      const [px, py, visible] = s.project(x, 0, z);
      const c = document.getElementById('scene');
      return visible && px >= 0 && px <= c.clientWidth && py >= 0 && py <= c.clientHeight;
    });
    s.streetKey = null;
    s.framed = null;
    return seen;
  });
  check(framed.every(Boolean), `four trees framed whole: ${framed.join(', ')}`);
  // 8. On a site the street's pruning cycles cut the trees, by default: at 20, when the line,
  // raising and building cycles all fall, the table says what was cut; unticked, the trees
  // are never cut and it says nothing of pruning.
  const pruned = () => page.evaluate(() => /pruned: \d+ cuts/.test(document.querySelector('#table').textContent));
  await page.selectOption('#site', 'narrow');
  check(await page.isChecked('#pruning') && !(await page.isDisabled('#pruning')), 'pruning on by default on a site');
  await page.evaluate(() => { age.value = 20; age.dispatchEvent(new Event('input')); });
  await waitUntil('the pruned growth tables', async () => (await page.evaluate(() => window.sylva.tables >= 2)) && (await pruned()), 120);
  if (shots) {
    await page.waitForTimeout(1500);
    await page.screenshot({ path: `${shots}/page-pruned-age-20.png` });
  }
  await page.uncheck('#pruning');
  await waitUntil('the uncut growth tables', async () => (await page.evaluate(() => window.sylva.tables >= 2)) && !(await pruned()), 120);
  check(true, 'the pruning box switches between the cut and the uncut trees');
  // 9. Queued work is visible: with growths of other species filling the memory bound (each
  // first growth of a species is expected to take the most any species takes per age), a
  // page that asks for one more says what it waits for, rather than hanging, and draws the
  // tree once there is room.
  const others = ['PRCE', 'FRAN_R', 'GLTR', 'CESI4'].map((code) =>
    fetch(`${server.url}api/growth?species=${code}&seed=5`).then((r) => r.status).catch((e) => e.message));
  await waitUntil('other growths under way', async () => (await (await fetch(`${server.url}api/status`)).json()).growing >= 1, 20);
  const queued = await browser.newPage({ viewport: { width: 1200, height: 800 } });
  watch(queued);
  await queued.goto(`${server.url}?species=MAGR`);
  const said = await waitUntil('the page saying what it waits for', () => queued.evaluate(() => {
    const text = document.getElementById('status').textContent;
    return /Waiting for \d+ growths? on the server/.test(text) && text;
  }), 30);
  check(true, `while other species grow, the page says: "${said}"`);
  await waitUntil('the queued species drawn', () => queued.evaluate(() => window.sylva?.firstTreeMs), 240);
  const othersDone = await Promise.all(others);
  check(othersDone.every((c) => c === 200 || c === 503), `the other growths answered ${othersDone.join(', ')}`);
  await queued.close();
  const worst = Math.max(...draws.map((d) => d.ms));
  console.log(`new age drawn after the slider stopped: ${draws.map((d) => `${d.age}: ${d.ms.toFixed(0)} ms (detail ${d.detail}, frame ${d.frame.toFixed(0)} ms, busy ${d.busy.toFixed(0)} ms)`).join(', ')}`);
  target('slowest new age drawn after the slider stopped', worst, 300);
  target('a frame of two 50-year leaf shells as the view turns', shells.turning, 100);
  target('the first frame of two 50-year leaf shells', shells.first, 100);
  check(!failed, 'no errors on the page');
} finally {
  await browser.close();
  await server.stop();
}

// In the page: the bark alone (leaves and street hidden) drawn black on white at pixel ratios
// 1 and 4. Blending black over white leaves each pixel at 255 times the share not covered, so
// the covered area is the sum of the pixels' darkness. Returns the share of the bark's pixels
// that are partly covered at ratio 1, and the covered area at both ratios, in pixels of ratio 1.
function thinStems() {
  const s = window.sylvaStreet;
  const gl = s.renderer.getContext();
  const hidden = [];
  const recoloured = new Map();
  s.site.visible = false;
  s.trees.traverse((o) => {
    if (!o.isMesh) return;
    if (!o.geometry.attributes._radius) { o.visible = false; hidden.push(o); return; }
    if (!recoloured.has(o.material)) recoloured.set(o.material, o.material.color.clone());
    o.material.color.setRGB(0, 0, 0);
  });
  const background = s.scene.background;
  s.scene.background = background.clone().setRGB(1, 1, 1);
  const ratio = s.renderer.getPixelRatio();
  const draw = (r) => {
    s.renderer.setPixelRatio(r);
    s.resize();
    const [w, h] = [gl.drawingBufferWidth, gl.drawingBufferHeight];
    const px = new Uint8Array(w * h * 4);
    gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, px);
    let area = 0, touched = 0, partial = 0;
    for (let i = 0; i < px.length; i += 4) {
      const dark = 1 - px[i + 1] / 255;
      area += dark;
      if (dark > 0.02) { touched++; if (dark < 0.98) partial++; }
    }
    return { area: area / (r * r), partial: partial / Math.max(1, touched) };
  };
  const one = draw(1);
  const four = draw(4);
  s.renderer.setPixelRatio(ratio);
  for (const [m, c] of recoloured) m.color.copy(c);
  for (const o of hidden) o.visible = true;
  s.site.visible = true;
  s.scene.background = background;
  s.resize();
  return { partial: one.partial, area: [one.area, four.area] };
}

// Prints a timing against its target; fails past five times the target.
function target(what, ms, most) {
  console.log(`${what}: ${ms.toFixed(0)} ms (target ${most} ms: ${ms <= most ? 'met' : 'MISSED'})`);
  check(ms <= 5 * most, `${what} within five times the target`);
}

function watch(page) {
  page.on('pageerror', (e) => { console.log(`page error: ${e.message}`); failed = true; });
  // A 503 is the server saying it is busy, which the page waits out (step 9).
  page.on('console', (m) => { if (m.type() === 'error' && !/status of 503/.test(m.text())) console.log(`console: ${m.text()}`); });
}

// Screenshot the page and measure it: leaf-green pixels under each tree's label (two trees),
// and each chart holding both species' colours.
async function look(page, a) {
  const png = await page.screenshot();
  if (shots) writeFileSync(`${shots}/page-age-${a}.png`, png);
  const found = await page.evaluate(async (b64) => {
    const blob = await (await fetch(`data:image/png;base64,${b64}`)).blob();
    const img = await createImageBitmap(blob);
    const c = new OffscreenCanvas(img.width, img.height);
    const g = c.getContext('2d');
    g.drawImage(img, 0, 0);
    const px = g.getImageData(0, 0, img.width, img.height).data;
    const at = (x, y) => { const i = 4 * (y * img.width + x); return [px[i], px[i + 1], px[i + 2]]; };
    const scene = document.getElementById('scene').getBoundingClientRect();
    const labels = [...document.querySelectorAll('#labels div')].map((d) => d.getBoundingClientRect());
    const half = labels.length > 1 ? (labels[1].left + labels[1].width / 2 - labels[0].left - labels[0].width / 2) * 0.4 : 100;
    const trees = labels.map((l) => {
      const cx = Math.round(l.left + l.width / 2);
      let leafy = 0;
      for (let x = Math.max(0, Math.round(cx - half)); x < Math.min(scene.right, cx + half); x++) {
        for (let y = Math.round(scene.top); y < scene.bottom; y++) {
          const [r, gr, b] = at(x, y);
          if (gr > r + 8 && gr > b + 8) leafy++;
        }
      }
      return leafy;
    });
    const colours = [[0x2f, 0x7d, 0x4f], [0xc0, 0x61, 0x2b]];
    const charts = [...document.querySelectorAll('#charts canvas')].map((cv) => {
      const r = cv.getBoundingClientRect();
      return colours.map((col) => {
        let n = 0;
        for (let x = Math.round(r.left); x < r.right; x++) {
          for (let y = Math.round(r.top); y < r.bottom; y++) {
            const p = at(x, y);
            if (Math.abs(p[0] - col[0]) + Math.abs(p[1] - col[1]) + Math.abs(p[2] - col[2]) < 60) n++;
          }
        }
        return n;
      });
    });
    return { trees, charts };
  }, png.toString('base64'));
  if (shots) {
    // The panel's lower half too: conflicts, each tree on its site, downloads.
    await page.waitForTimeout(1000);
    await page.evaluate(() => { document.querySelector('aside').scrollTop = 1e6; });
    await page.screenshot({ path: `${shots}/page-age-${a}-panel.png` });
    await page.evaluate(() => { document.querySelector('aside').scrollTop = 0; });
  }
  console.log(`age ${a}: leaf pixels per tree ${found.trees.join(', ')}; species colours per chart ${found.charts.map((c) => c.join('/')).join(', ')}`);
  check(found.trees.length === 2 && found.trees.every((n) => n > 400), `age ${a}: two trees drawn`);
  check(found.charts.length === 4 && found.charts.every((c) => c.every((n) => n > 40)), `age ${a}: four charts drawn, both species on each`);
}
