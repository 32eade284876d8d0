// A soak of `sylva serve` on 127.0.0.1: 20 clients for a bounded time, each asking, one
// request after another on its own keep-alive connection, what an office of planners asks:
// growth tables and CSVs of 1 to 3 species on the typical position and the built-in sites,
// pruned or not, trees as GLB at ages 1 to 60 and details 2 to 4, now and then a picture, a
// plan symbol or a site drawing, the city's tiles and reports (with --city), and the small
// JSON answers. Every second it reads /api/status and the server's resident memory
// (/proc/PID/status: VmRSS now, VmHWM the most so far).
//
// It asserts what the server promises, never a time:
// - `cache_bytes` never above `cache_bound` in any reading;
// - every answer is 200, 503 (busy, with Retry-After) or 507 (a species larger than the
//   bound); never another error, and the server stays up;
// - the most resident memory (VmHWM) within the bound plus the stated overhead
//   (--overhead-mib, the README's figure).
// It prints, each minute, the answers by code, `cache_bytes` against the bound, resident
// memory and the slowest answer; --json FILE writes them. The overhead is resident memory
// less `cache_bytes`, read together each second: what growths and requests build while they
// run, the program, and the allocator's slack.
//
// With --against OTHER (the same program built on another allocator: `cargo build --features
// sylva-cli/mimalloc`), the same soak runs again on OTHER and the two are set side by side:
// peak resident memory and the overhead's mean and most, with their ratios.
//
//   node soak.mjs path/to/sylva [--minutes 2] [--cache-mib 256] [--overhead-mib N]
//        [--city DIR] [--clients 20] [--json FILE] [--against path/to/other]

import { readFileSync, writeFileSync, readdirSync, statSync } from 'node:fs';
import { join, relative, basename } from 'node:path';
import { startServer } from './common.mjs';

const args = process.argv.slice(2);
const bin = args[0];
const opt = (name, fallback) => {
  const i = args.indexOf(`--${name}`);
  return i >= 0 ? args[i + 1] : fallback;
};
const minutes = Number(opt('minutes', 2));
const cacheMib = opt('cache-mib', null);
const cityDir = opt('city', null);
const CLIENTS = Number(opt('clients', 20));
// The overhead the README states for resident memory above the bound: what growths and
// requests build while they run, the program itself and the allocator's slack.
const overheadMib = Number(opt('overhead-mib', 1024));
if (!bin) { console.log('usage: node soak.mjs path/to/sylva [--minutes N] ...'); process.exit(2); }

const kb = (b) => Math.round(b / (1 << 20));
const extra = [];
if (cacheMib) extra.push('--cache-mib', cacheMib);
if (cityDir) extra.push('--city', cityDir);
const failures = [];
const runs = [];
for (const b of [bin, opt('against', null)].filter(Boolean)) runs.push(await soak(b));
if (runs.length === 2) {
  const [a, b] = runs;
  const r = (x, y) => (y / x).toFixed(2);
  console.log(`allocators side by side: ${a.allocator} against ${b.allocator}: peak resident ${kb(a.peak)} vs ` +
    `${kb(b.peak)} MiB (${r(a.peak, b.peak)}x); overhead over cache_bytes mean ${kb(a.overheadMean)} vs ` +
    `${kb(b.overheadMean)} MiB (${r(a.overheadMean, b.overheadMean)}x), most ${kb(a.overheadMost)} vs ` +
    `${kb(b.overheadMost)} MiB (${r(a.overheadMost, b.overheadMost)}x); answered ${a.codes[200] ?? 0} vs ${b.codes[200] ?? 0}`);
}
if (opt('json', null)) writeFileSync(opt('json'), JSON.stringify(runs, null, 1));
if (failures.length) {
  console.log(`FAILED: ${failures.length} problems, the first: ${failures.slice(0, 10).join('; ')}`);
  process.exit(1);
}

async function soak(bin) {
  const server = await startServer(bin, extra);
  const api = (path) => `${server.url}api/${path}`;
  const rand = (n) => Math.floor(Math.random() * n);
  const pick = (xs) => xs[rand(xs.length)];

  // The species of the mix: Modesto's, from the smallest growth (the flowering cherry, some
  // 90 MB through its ages) to the largest (holly oak, 500 MB), with the page's two.
  const CODES = ['PLAC', 'PICH', 'ZESE', 'GLTR', 'PRCE', 'LAIN', 'MAGR', 'QUIL2'];
  const species = (await (await fetch(api('species?region=InlVal'))).json())
    .filter((s) => CODES.includes(s.code));
  const sites = ['narrow', 'boulevard', 'facade'];
  const growthOf = () => {
    const p = new URLSearchParams({ species: pick(species).code, seed: String(rand(2)) });
    if (Math.random() < 0.5) p.set('site', pick(sites));
    if (Math.random() < 0.3) p.set('pruning', 'on');
    return p;
  };
  const cityFiles = [];
  if (cityDir) {
    const name = basename(cityDir);
    const walk = (dir) => {
      for (const f of readdirSync(dir)) {
        const path = join(dir, f);
        if (statSync(path).isDirectory()) walk(path);
        else if (/\.(json|glb|subtree|html|csv)$/.test(f)) cityFiles.push(`city/${name}/${relative(cityDir, path)}`);
      }
    };
    walk(cityDir);
  }
  const treeOf = () => {
    const s = pick(species);
    const [first, last] = s.ages;
    const age = Math.min(last, Math.max(first, 1 + rand(60)));
    const p = growthOf();
    p.set('age', String(age));
    p.set('detail', String(2 + rand(3)));
    p.set('species', s.code);
    p.delete('site');
    return p;
  };
  // Weights: what a page asks most (trees as its slider moves, growth tables), then the rest.
  const MIX = [
    [30, () => `api/tree.glb?${treeOf()}`],
    [14, () => `api/growth?${growthOf()}`],
    [6, () => {
      const p = growthOf();
      const codes = new Set([p.get('species')]);
      for (let n = rand(3); n > 0; n--) codes.add(pick(species).code);
      p.set('species', [...codes].join(','));
      return `api/table.csv?${p}`;
    }],
    [2, () => { const p = treeOf(); p.delete('detail'); return `api/plan.svg?${p}`; }],
    [2, () => { const p = treeOf(); p.delete('detail'); p.set('site', pick(sites)); return `api/site.png?${p}`; }],
    [1, () => {
      const p = treeOf();
      p.delete('detail');
      const [a, b] = [pick(species), pick(species)];
      // An age both species' data cover.
      const first = Math.max(a.ages[0], b.ages[0], 1);
      const last = Math.min(a.ages[1], b.ages[1]);
      p.set('species', `${a.code},${b.code}`);
      p.set('age', String(first + rand(last - first + 1)));
      return `api/compare.png?${p}&size=640x360`;
    }],
    [cityFiles.length ? 25 : 0, () => pick(cityFiles)],
    [cityFiles.length ? 3 : 0, () => 'api/cities'],
    [12, () => pick(['api/regions', 'api/species?region=InlVal', 'api/sites', 'api/status'])],
  ];
  const total = MIX.reduce((a, [w]) => a + w, 0);
  const nextPath = () => {
    let r = Math.random() * total;
    for (const [w, make] of MIX) { if ((r -= w) < 0) return make(); }
    return MIX[0][1]();
  };

  const memory = () => {
    const status = readFileSync(`/proc/${server.pid}/status`, 'utf8');
    const field = (name) => Number(status.match(new RegExp(`${name}:\\s+(\\d+) kB`))[1]) * 1024;
    return { rss: field('VmRSS'), peak: field('VmHWM') };
  };

  const t0 = Date.now();
  const end = t0 + minutes * 60000;
  let minute = { codes: {}, slowest: 0, slowestPath: '', cacheMax: 0, answers: 0 };
  const minutesSeen = [];
  let readings = 0;
  const overheads = [];
  let bound = 0;
  let last = null;

  async function client() {
    while (Date.now() < end) {
      const path = nextPath();
      const started = performance.now();
      let code = 0;
      try {
        const r = await fetch(`${server.url}${path}`);
        await r.arrayBuffer();
        code = r.status;
        if (code === 503 && !r.headers.get('retry-after')) failures.push(`503 without Retry-After: ${path}`);
        if (![200, 503, 507].includes(code)) failures.push(`${code}: ${path}`);
        if (code === 503) await new Promise((ok) => setTimeout(ok, 1000 * Number(r.headers.get('retry-after') || 1)));
      } catch (e) {
        failures.push(`${path}: ${e.message}`);
        code = 'error';
        await new Promise((ok) => setTimeout(ok, 1000));
      }
      const ms = performance.now() - started;
      minute.codes[code] = (minute.codes[code] ?? 0) + 1;
      minute.answers++;
      if (ms > minute.slowest) { minute.slowest = ms; minute.slowestPath = path; }
    }
  }

  async function sampler() {
    while (Date.now() < end) {
      try {
        const s = await (await fetch(api('status'))).json();
        readings++;
        bound = s.cache_bound;
        minute.cacheMax = Math.max(minute.cacheMax, s.cache_bytes);
        if (s.cache_bytes > s.cache_bound) failures.push(`cache_bytes ${s.cache_bytes} > cache_bound ${s.cache_bound}`);
        last = { ...s, ...memory() };
        overheads.push(last.rss - s.cache_bytes);
      } catch (e) {
        failures.push(`status: ${e.message}`);
      }
      if (Date.now() - t0 >= (minutesSeen.length + 1) * 60000) closeMinute();
      await new Promise((ok) => setTimeout(ok, 1000));
    }
  }

  // The minute's line: answers by code, the most cache_bytes read against the bound, resident
  // memory now and at most, the slowest answer.
  function closeMinute() {
    const m = { minute: minutesSeen.length + 1, ...minute, rss: last?.rss, peak: last?.peak,
      cache_bytes: last?.cache_bytes, growths: last?.growths, refused: last?.refused };
    minutesSeen.push(m);
    console.log(`minute ${m.minute}: ${m.answers} answers ${JSON.stringify(m.codes)}; cache ${kb(m.cacheMax)} MiB most, ` +
      `${kb(m.cache_bytes)} MiB now (bound ${kb(bound)} MiB), resident ${kb(m.rss)} MiB now, ${kb(m.peak)} MiB most; ` +
      `slowest ${(m.slowest / 1000).toFixed(1)} s (${m.slowestPath})`);
    minute = { codes: {}, slowest: 0, slowestPath: '', cacheMax: 0, answers: 0 };
  }

  console.log(`soak: ${CLIENTS} clients for ${minutes} min on ${server.url} (${extra.join(' ') || 'defaults'}), ` +
    `${species.length} species, ${cityFiles.length} city files`);
  await Promise.all([sampler(), ...Array.from({ length: CLIENTS }, client)]);
  const status = await (await fetch(api('status'))).json();
  last = { ...status, ...memory() };
  minute.cacheMax = Math.max(minute.cacheMax, status.cache_bytes);
  if (minute.answers > 0) closeMinute();
  const { rss, peak } = last;
  await server.stop();

  const codes = {};
  for (const m of minutesSeen) for (const [k, v] of Object.entries(m.codes)) codes[k] = (codes[k] ?? 0) + v;
  const slowest = minutesSeen.reduce((a, m) => (m.slowest > a.slowest ? m : a), { slowest: 0 });
  console.log(`in all: ${JSON.stringify(codes)}; slowest ${(slowest.slowest / 1000).toFixed(1)} s (${slowest.slowestPath}); ` +
    `${readings} status readings, cache_bytes at most ${kb(Math.max(...minutesSeen.map((m) => m.cacheMax)))} MiB of ${kb(bound)} MiB; ` +
    `at the end cache_bytes ${kb(status.cache_bytes)} MiB and resident ${kb(rss)} MiB; resident ${kb(peak)} MiB at most (bound + ${overheadMib} MiB = ${kb(bound) + overheadMib} MiB); ` +
    `allocator ${status.allocator}; refused ${JSON.stringify(status.refused)}`);
  const overheadMean = overheads.reduce((a, x) => a + x, 0) / Math.max(1, overheads.length);
  const overheadMost = Math.max(...overheads);
  console.log(`overhead (resident less cache_bytes): mean ${kb(overheadMean)} MiB, most ${kb(overheadMost)} MiB`);

  const check = (ok, message) => { if (!ok) failures.push(message); else console.log(`ok: ${message}`); };
  check(readings >= minutes * 30, `the status was read ${readings} times`);
  check(!failures.some((f) => f.startsWith('cache_bytes')), 'cache_bytes never above cache_bound');
  check((codes[200] ?? 0) > 0, 'answers came');
  check(peak <= bound + overheadMib * (1 << 20), `resident memory at most ${kb(peak)} MiB, within the bound and ${overheadMib} MiB`);
  return { allocator: status.allocator, minutes: minutesSeen, codes, peak, rss, bound, overheadMean, overheadMost,
    slowest: slowest.slowest, slowestPath: slowest.slowestPath, final: status };
}
