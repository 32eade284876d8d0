// The city view in a real browser (the system's Chromium through playwright-core, WebGL on
// SwiftShader where there is no GPU): `sylva serve --city` on a demo city at two epochs, beside
// folders that are no city. It opens the city, moves the epoch slider, clicks a tree and reads
// its card, filters by species, checks the report's totals against a sum over the tiles'
// property tables, and that nothing outside the given folders is served. Prints the issue's
// timings: trees shown after opening (target 5 s), frames a second while turning (10), a
// click's answer (300 ms), and the server's memory.
//
//   node city.mjs path/to/sylva SHOTS [CITY] [--prepared DIR]
//
// Without CITY it writes a small demo city itself, and the same trees spread over kilometres
// (demo-cities.mjs), or takes them from DIR where demo-cities.mjs wrote them already; with
// CITY (a folder `sylva city` wrote, such as the 100,000-tree demo) it times that one.

import { chromium } from 'playwright-core';
import { spawnSync } from 'node:child_process';
import { mkdirSync, mkdtempSync, readFileSync, writeFileSync, rmSync, copyFileSync } from 'node:fs';
import { createServer } from 'node:http';
import { request } from 'node:http';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { startServer, waitUntil, check } from './common.mjs';
import { propertyTable } from './glb.mjs';
import { writeDemoCities, demoCitiesIn } from './demo-cities.mjs';

const args = process.argv.slice(2);
const at = args.indexOf('--prepared');
const prepared = at >= 0 ? args.splice(at, 2)[1] : null;
const bin = args[0] || new URL('../../../../target/debug/sylva', import.meta.url).pathname;
const shots = args[1] || null;
const given = args[2] || null;
if (shots) mkdirSync(shots, { recursive: true });
const work = mkdtempSync(join(tmpdir(), 'sylva-city-view-'));

// 1. The cities: a demo city at two epochs, and three folders that are none.
let city = given;
let sparse = null;
if (!city) {
  const demo = prepared ? demoCitiesIn(prepared) : writeDemoCities(bin, join(work, 'demo'));
  city = demo.city;
  sparse = demo.sparse;
  // Its planting plans (--dxf) and what they are drawn from, for ezdxf in pytest
  // (crates/sylva-py/tests/test_cad.py reads SHOTS/dxf).
  if (shots) {
    mkdirSync(join(shots, 'dxf'), { recursive: true });
    copyFileSync(demo.csv, join(shots, 'dxf', 'demo.csv'));
    copyFileSync(join(city, 'summary.json'), join(shots, 'dxf', 'summary.json'));
    for (const y of [0, 20]) copyFileSync(join(city, `year-${y}`, 'planting-plan.dxf'), join(shots, 'dxf', `planting-plan-${y}.dxf`));
  }
}
const name = city.split('/').filter(Boolean).pop();
const notCity = join(work, 'holiday-photos');
mkdirSync(notCity);
writeFileSync(join(notCity, 'beach.jpg'), 'not a picture');
const damaged = join(work, 'damaged');
mkdirSync(damaged);
writeFileSync(join(damaged, 'summary.json'), readFileSync(join(city, 'summary.json'), 'utf8').slice(0, 200));
const other = join(work, 'other-tool');
mkdirSync(other);
writeFileSync(join(other, 'summary.json'), JSON.stringify({ generator: 'py3dtiles 7.0', epochs: [] }));
writeFileSync(join(other, 'tileset.json'), JSON.stringify({ asset: { version: '1.0' }, root: {} }));

// Two cities of one name, and a missing folder, stop the server at start with a message.
const twin = join(work, 'twin', name);
mkdirSync(twin, { recursive: true });
copyFileSync(join(city, 'summary.json'), join(twin, 'summary.json'));
for (const [what, args, says] of [
  ['two cities of one name', ['--city', city, '--city', twin], /two cities named/],
  ['a missing folder', ['--city', join(work, 'nowhere')], /--city .*nowhere/],
]) {
  const r = spawnSync(bin, ['serve', '--port', '0', ...args], { encoding: 'utf8', timeout: 20000 });
  check(r.status !== 0 && r.status !== 101 && says.test(r.stderr), `${what}: refused at start (exit ${r.status}): ${r.stderr.trim().split('\n').pop()}`);
}

// A map tile source on this machine for --basemap: any tile is one small PNG.
const png = Buffer.from('iVBORw0KGgoAAAANSUhEUgAAAAIAAAACCAIAAAD91JpzAAAAEklEQVR4nGM4cWnfiUv7GCAUAEHWCWEv9sFeAAAAAElFTkSuQmCC', 'base64');
const mapAsked = [];
const mapServer = createServer((req, res) => {
  mapAsked.push(req.url);
  res.writeHead(200, { 'content-type': 'image/png', 'access-control-allow-origin': '*' });
  res.end(png);
}).listen(0, '127.0.0.1');
await new Promise((ok) => mapServer.once('listening', ok));
const basemap = `http://127.0.0.1:${mapServer.address().port}/{z}/{x}/{y}.png`;

const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
  args: ['--no-sandbox', '--disable-quic', '--no-first-run', '--disable-background-networking',
    '--disable-component-update', '--disable-sync', '--use-angle=swiftshader',
    '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist'],
});
const server = await startServer(bin, ['--city', city, '--city', notCity, '--city', damaged, '--city', other, '--basemap', basemap,
  ...(sparse ? ['--city', sparse] : [])]);
let failed = false;
try {
  // 2. The API lists every city, the broken ones with why.
  const listed = await (await fetch(`${server.url}api/cities`)).json();
  const by = Object.fromEntries(listed.cities.map((c) => [c.name, c]));
  check(by[name] && !by[name].problem && by[name].epochs.length === (given ? by[name].epochs.length : 2), `${name}: listed with its epochs`);
  check(/no summary\.json/.test(by['holiday-photos']?.problem), `a folder that is no city: ${by['holiday-photos']?.problem}`);
  check(/damaged/.test(by.damaged?.problem), `a damaged summary.json: ${by.damaged?.problem}`);
  check(/written by `py3dtiles 7\.0`/.test(by['other-tool']?.problem), `another tool's folder: ${by['other-tool']?.problem}`);

  // 3. Nothing outside the given folders, and nothing hidden or unlisted in them.
  for (const path of [`/city/${name}/../summary.json`, `/city/${name}/%2e%2e/%2e%2e/etc/passwd`,
    `/city/${name}//etc/passwd`, `/city/${name}/%2Fetc%2Fpasswd`, `/city/holiday-photos/beach.jpg`,
    `/city/${name}/year-0/../../summary.json`, '/city/nowhere/summary.json']) {
    const status = await rawGet(server.url, path);
    check(status === 404, `${path}: ${status}`);
  }
  check((await fetch(`${server.url}city/${name}/summary.json`)).status === 200, 'a listed file is served');

  // 4. The page: trees within 5 s of opening.
  const page = await browser.newPage({ viewport: { width: 1600, height: 1000 } });
  page.on('pageerror', (e) => { console.log(`page error: ${e.message}`); failed = true; });
  page.on('console', (m) => { if (m.type() === 'error') console.log(`console: ${m.text()}`); });
  await page.goto(`${server.url}city.html?city=${encodeURIComponent(name)}`);
  const firstMs = await waitUntil('the first trees', () => page.evaluate(() => window.sylvaCity?.firstTreesMs), 60);
  target('page opened to the first trees drawn', firstMs, 5000);
  await waitUntil('the first epoch loaded', () => page.evaluate(() => window.sylvaCity.shownEpoch != null), 120);
  console.log(`page opened to every tile of the default view drawn: ${(await page.evaluate(() => window.sylvaCity.shownMs)).toFixed(0)} ms`);
  const problems = await page.locator('#problem-list li').allTextContents();
  check(problems.length === 3, `the page lists the three folders it cannot show: ${problems.map((p) => p.split(':')[0]).join(', ')}`);
  check(mapAsked.length > 0, `the basemap's tiles were asked for (${mapAsked.length}, e.g. ${mapAsked[0]})`);
  const drawn = await waitUntil('the basemap drawn', () => page.evaluate(() => window.sylvaCity.basemapDrawn), 30);
  check(drawn === mapAsked.length, `every basemap tile asked for lies under the trees (${drawn})`);
  if (shots) writeFileSync(`${shots}/city-epoch-0.png`, await page.screenshot());
  await fitted(page, name);

  // 5. Frames a second while turning at the default view.
  console.log(`drawn at the default view: ${JSON.stringify(await page.evaluate(() => window.sylvaCity.drawn()))}`);
  const turn = await page.evaluate(() => window.sylvaCity.turn(4000));
  const fps = (1000 * turn.frames) / turn.ms;
  console.log(`turning at the default view: ${fps.toFixed(1)} frames a second (target 10: ${fps >= 10 ? 'met' : 'MISSED'})`);
  check(fps >= 2, 'turning at two frames a second or better');

  // 6. A click on a tree, or on a tree's marker, opens its card. The card's first growth is
  // answered as a busy server answers (503, Retry-After, the growths it waits for): the card
  // must say what it waits for, ask again, and draw its charts.
  let busy = 0;
  await page.route('**/api/growth?*', (route) => (busy++ > 0 ? route.continue() : route.fulfill({
    status: 503,
    headers: { 'Retry-After': '1' },
    contentType: 'application/json',
    body: JSON.stringify({ error: 'busy: 3 growths under way', growing: 3, retry_after: 1 }),
  })));
  const points = await page.evaluate(() => [...window.sylvaCity.treePoints(12), ...window.sylvaCity.markerPoints(12)]);
  check(points.length > 0, `${points.length} trees on the screen to click`);
  let opened = null;
  for (const p of points) {
    const before = await page.evaluate(() => window.sylvaCity.clicks.length);
    await page.mouse.click(p.x, p.y);
    const click = await waitUntil('the click answered', () => page.evaluate((n) => window.sylvaCity.clicks[n], before), 10);
    if (click.id != null) { opened = click; break; }
  }
  check(opened, `a click on a tree opened its card (tree ${opened?.id})`);
  target('a click answered with its card', opened.ms, 300);
  const title = await page.textContent('#card-title');
  check(title.includes(`tree ${opened.id}`), `the card is tree ${opened.id}'s: ${title}`);
  const card = await page.textContent('#card-table');
  check(/Inventory row/.test(card) && /Grown as/.test(card) && /DBH/.test(card), 'the card gives its inventory row, what it is grown as and its DBH');
  check(/Condition(good|fair|poor), as the inventory recorded it/.test(card), 'the card gives the condition the inventory recorded');
  const href = await page.getAttribute('#street-link', 'href');
  check(/^\/\?region=\w+&species=\w+&age=\d+$/.test(href), `the card links to the street page: ${href}`);
  await waitUntil('the card\'s charts', () => page.evaluate(() => window.sylvaCity.cardCharts > 0), 240);
  // The first message answers the 503 given here; the server itself may still be busy with
  // the growths it starts with when the card asks again, and say so after it.
  const waited = await page.evaluate(() => window.sylvaCity.cardWaited || []);
  check(busy >= 2 && /Waiting for 3 growths on the server/.test(waited[0]), `a busy server's 503 waited out: the card said "${waited.join('", then "')}", then drew its charts`);
  await page.unroute('**/api/growth?*');
  if (shots) writeFileSync(`${shots}/city-card.png`, await page.screenshot());

  // 7. The epoch slider swaps the tileset in place.
  const epochs = by[name].epochs;
  await page.focus('#epoch');
  await page.keyboard.press('End');
  await waitUntil('the last epoch loaded', () => page.evaluate((y) => window.sylvaCity.shownEpoch === y, epochs[epochs.length - 1].years), 120);
  check((await page.textContent('#epoch-label')).includes(`+${epochs[epochs.length - 1].years}`), `the slider shows +${epochs[epochs.length - 1].years} years`);
  if (shots) writeFileSync(`${shots}/city-epoch-${epochs[epochs.length - 1].years}.png`, await page.screenshot());

  // 8. A species filter dims every other tree.
  const report = JSON.parse(readFileSync(join(city, 'report.json'), 'utf8'));
  const common = report.species[0].code;
  await page.selectOption('#f-species', common);
  const lit = await page.evaluate(() => window.sylvaCity.lit());
  check(lit.dim > 0 && lit.lit > 0, `filtering ${common}: ${lit.lit} trees lit, ${lit.dim} dimmed`);
  await page.selectOption('#f-species', '');
  // A condition filter dims every tree of another condition, and the report panel says the
  // condition the inventory recorded.
  await page.selectOption('#f-condition', 'poor');
  const poor = await page.evaluate(() => window.sylvaCity.lit());
  check(poor.dim > 0 && poor.lit > 0 && poor.lit < poor.dim, `filtering poor trees: ${poor.lit} lit, ${poor.dim} dimmed`);
  await page.selectOption('#f-condition', '');
  const said = await page.textContent('#report-condition');
  check(/\d+% good, \d+% fair, \d+% poor/.test(said) && said.includes('best:'), `the report panel gives the condition: ${said.slice(0, 90)}…`);

  // 9. The report's totals against a sum over the tiles' property tables (each epoch's leaf
  // tiles hold every tree once).
  for (const [i, e] of epochs.entries()) {
    const sum = sumTiles(join(city, by[name].epochs[i].tileset.replace(`/city/${name}/`, '')));
    const r = report.epochs[i];
    check(r.years === e.years && r.trees === sum.trees, `+${e.years}: the report's ${r.trees} trees are the tiles' ${sum.trees}`);
    close(r.benefits_usd, sum.benefits, `+${e.years}: the report's benefits $${r.benefits_usd.toFixed(2)} are the tiles' sum`);
    close(r.typical_total_usd, sum.typical, `+${e.years}: the report's i-Tree benefits $${r.typical_total_usd.toFixed(2)} are the tiles' sum`);
    // The first epoch's ages by species (the tiles hold each tree's age as f32).
    if (i > 0) continue;
    const off = report.species.filter((s) => {
      const a = sum.ages[s.code];
      return !a || a.trees !== s.trees || Math.abs(a.years / a.trees - s.mean_age_years) > 1e-3 * Math.max(1, s.mean_age_years);
    });
    check(off.length === 0, `each species' trees and mean age in the report are the tiles' (${report.species.length} species${off.length ? `; not: ${off.map((s) => s.code).join(', ')}` : ''})`);
    // Each tree's condition in the tiles is the report's count (the demo's census `health`).
    const [g, f, p] = report.observed.good_fair_poor;
    const c = sum.condition;
    check((c.good || 0) === g && (c.fair || 0) === f && (c.poor || 0) === p && (c.none || 0) === report.observed.not_recorded,
      `the tiles' conditions (${JSON.stringify(c)}) are the report's (${g} good, ${f} fair, ${p} poor)`);
    // The census's problems sit beside Sylva's site model: each species with problems
    // recorded is set on the typical street, and some reach into its lines' clearance.
    const codes = new Set(report.observed.problems.map((r) => r.code));
    check(report.predicted.length === codes.size && report.predicted.some((p) => p.wire && p.wire.dbh_cm > 0),
      `the report sets ${report.predicted.length} species on the typical street beside the problems recorded`);
  }
  // Beside Modesto's published benefits per tree (McPherson et al. 1999), held to within the
  // factors docs/benefits.md explains (prices and population), aesthetics included.
  if (!given) check(report.published, 'an Inland Valleys city is set beside Modesto\'s published figures');
  if (report.published) {
    const c = report.published;
    const row = (k) => c.rows.find((r) => r[0] === k);
    check(c.published.city === 'Modesto' && row('total')[2] === 54.33, `the report sets the city beside ${c.published.city}'s $${row('total')[2]} a tree`);
    const typical = [0, 1, 2, 3, 4].map((k) => report.species.reduce((a, s) => a + (s.typical_usd[k] || 0), 0) / report.trees);
    check(typical.every((v, k) => Math.abs(v - report.typical_per_tree_usd[k]) < 1e-9), 'its per-tree figures are the species\' sums over the trees');
    const ours = row('total')[1], theirs = row('total')[2];
    console.log(`per tree: ${c.rows.map((r) => `${r[0]} ${r[1] == null ? '–' : r[1].toFixed(2)} vs ${r[2]}`).join(', ')}`);
    check(ours > theirs / 1.5 && ours < theirs * 1.5, `all five categories, $${ours.toFixed(2)} a tree, within a factor of 1.5 of Modesto's $${theirs.toFixed(2)}`);
    check(row('aesthetics_other')[1] > 0, `aesthetics priced: $${row('aesthetics_other')[1]?.toFixed(2)} a tree against Modesto's $${row('aesthetics_other')[2]}`);
    check(report.own_per_tree_usd[0] == null && report.own_per_tree_usd.slice(1).every((v) => v > 0),
      'Sylva\'s own figures: every category but energy (no façades), which is said not computed');
  }
  const shown = await page.$$eval('#report-epochs td[data-k=trees]', (cells) => cells.map((c) => c.textContent));
  check(shown[0] === report.epochs[0].trees.toLocaleString('en-US'), `the page's report shows ${shown[0]} trees at the first epoch`);
  // The full report in its frame, as a reader sees it.
  const frame = page.frameLocator('#report-frame');
  await frame.locator('h1').waitFor({ timeout: 30000 });
  const headings = await frame.locator('h2').allTextContents();
  check(['Families', 'Genera', 'Not computed'].every((h) => headings.includes(h)), `the report's page has its sections: ${headings.join(', ')}`);
  check(/Estimated age/.test(await frame.locator('table').first().textContent()), 'the report gives each species\' estimated ages');
  if (shots) {
    await page.locator('#report').scrollIntoViewIfNeeded();
    await page.waitForTimeout(1000);
    writeFileSync(`${shots}/city-report.png`, await page.screenshot());
  }

  // 10. A sparse inventory over kilometres: every tree in the opening view, as a marker where
  // its crown is too small to see, and a marker's click opens its tree's card.
  if (sparse) {
    await page.goto(`${server.url}city.html?city=sparse-census`);
    await waitUntil('the sparse city\'s trees', () => page.evaluate(() => window.sylvaCity.shownEpoch != null), 120);
    const extent = await page.evaluate(() => window.sylvaCity.fitted.extent);
    check(Math.min(...extent) > 2000, `the sparse city spreads over ${extent.map((m) => (m / 1000).toFixed(1)).join(' by ')} km`);
    await fitted(page, 'sparse-census');
    const drawn = await page.evaluate(() => window.sylvaCity.drawn());
    check(drawn.markers > 0.5 * 300, `at the opening view most of its trees are markers (${drawn.markers}), each in its species' colour`);
    const legend = await page.locator('#legend span').count();
    check(legend > 1, `the legend names the markers' colours (${legend} entries)`);
    if (shots) writeFileSync(`${shots}/city-sparse.png`, await page.screenshot());
    const marks = await page.evaluate(() => window.sylvaCity.markerPoints(6));
    let card = null;
    for (const m of marks) {
      const before = await page.evaluate(() => window.sylvaCity.clicks.length);
      await page.mouse.click(m.x, m.y);
      const click = await waitUntil('the marker\'s click answered', () => page.evaluate((n) => window.sylvaCity.clicks[n], before), 10);
      if (click.id === m.id) { card = click; break; }
    }
    check(card, `a click on a marker opened its tree's card (tree ${card?.id})`);
    check((await page.textContent('#card-title')).includes(`tree ${card.id}`), 'the card is the marker\'s tree\'s');
  }

  // 10. The server's memory.
  const rss = Number(readFileSync(`/proc/${server.pid}/status`, 'utf8').match(/VmRSS:\s+(\d+)/)[1]) / 1024;
  console.log(`the server's memory after the tests: ${rss.toFixed(0)} MB (its cache bound: 1024 MB of grown trees)`);
  check(rss < 1024 + 512, 'the server stays under its cache bound and its growths');
} catch (e) {
  console.log(String(e.stack || e));
  failed = true;
} finally {
  await browser.close();
  await server.stop();
  mapServer.close();
  rmSync(work, { recursive: true, force: true });
}
if (failed) process.exit(1);

// The opening view holds every tree of the loaded tiles (its fitted view, issue X).
async function fitted(page, label) {
  const at = await page.evaluate(() => window.sylvaCity.treesInPicture());
  check(at.all > 0 && at.inside === at.all, `${label}: the opening view holds all ${at.all} trees of its tiles (${at.inside} inside the picture)`);
}

// A census-layout CSV (latitude and longitude columns) with every tree's distance from the
// first multiplied by `k`: the same trees along streets `k` times longer.
function target(what, ms, most) {
  console.log(`${what}: ${ms.toFixed(0)} ms (target ${most} ms: ${ms <= most ? 'met' : 'MISSED'})`);
  check(ms <= 5 * most, `${what} within five times the target`);
}

function close(a, b, what) {
  check(Math.abs(a - b) <= 1e-4 * Math.max(1, Math.abs(a)), `${what} (${b.toFixed(2)})`);
}

// A GET sent as written, so that `..` and `//` reach the server unchanged.
function rawGet(base, path) {
  const u = new URL(base);
  return new Promise((ok, fail) => {
    const req = request({ host: u.hostname, port: u.port, path, method: 'GET' }, (res) => { res.resume(); ok(res.statusCode); });
    req.on('error', fail);
    req.end();
  });
}

// Every leaf tile's property table of a tileset: trees, and benefits summed.
function sumTiles(tilesetPath) {
  const dir = tilesetPath.slice(0, tilesetPath.lastIndexOf('/') + 1);
  const json = JSON.parse(readFileSync(tilesetPath, 'utf8'));
  const sum = { trees: 0, benefits: 0, typical: 0, ages: {}, condition: {} };
  const walk = (tile) => {
    if (tile.children?.length) { tile.children.forEach(walk); return; }
    if (!tile.content) return;
    const t = propertyTable(readFileSync(dir + tile.content.uri));
    if (!t) return;
    sum.trees += t.count;
    for (let i = 0; i < t.count; i++) {
      sum.benefits += t.get('benefits_usd_per_year', i);
      sum.typical += t.get('typical_benefits_usd_per_year', i);
      const a = (sum.ages[t.get('species', i)] ||= { trees: 0, years: 0 });
      a.trees += 1;
      a.years += t.get('age_years', i);
      if (t.get('species', i) !== 'stump') {
        const c = t.get('condition', i) || 'none';
        sum.condition[c] = (sum.condition[c] || 0) + 1;
      }
    }
  };
  walk(json.root);
  return sum;
}
