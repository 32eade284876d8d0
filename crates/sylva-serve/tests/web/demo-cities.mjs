// The city view's demo cities, written by `sylva` into DIR: a 300-tree demo inventory of
// Modesto at two epochs with its report and planting plans (DIR/modesto-demo, from
// DIR/demo.csv), and the same trees spread over kilometres, as sparse as a census sample
// (DIR/sparse-census; issue X: a real inventory opened on empty ground). One cache of grown
// trees serves both, so the sparse city grows nothing again.
//
//   node demo-cities.mjs path/to/sylva DIR
//
// city.mjs calls it itself; CI runs it alone beforehand, at a low priority on the cores other
// steps leave idle, and hands city.mjs the folder (--prepared DIR).

import { execFileSync } from 'node:child_process';
import { mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { pathToFileURL } from 'node:url';

export function writeDemoCities(bin, dir) {
  mkdirSync(dir, { recursive: true });
  const t0 = Date.now();
  const csv = join(dir, 'demo.csv');
  execFileSync(bin, ['city-demo', '-o', csv, '--trees', '300', '--region', 'InlVal', '--seed', '3'], { stdio: 'ignore' });
  const cache = ['--cache', join(dir, 'grown')];
  const city = join(dir, 'modesto-demo');
  execFileSync(bin, ['city', csv, '-o', city, '--years', '0,20', '--report', '--dxf', '--variants', '1', ...cache], { stdio: 'ignore' });
  const sparse = join(dir, 'sparse-census');
  writeFileSync(join(dir, 'sparse.csv'), spread(readFileSync(csv, 'utf8'), 12));
  execFileSync(bin, ['city', join(dir, 'sparse.csv'), '-o', sparse, '--years', '0', '--variants', '1', ...cache], { stdio: 'ignore' });
  console.log(`demo cities written in ${((Date.now() - t0) / 1000).toFixed(1)} s`);
  return { csv, city, sparse };
}

// The same folders, once written.
export function demoCitiesIn(dir) {
  return { csv: join(dir, 'demo.csv'), city: join(dir, 'modesto-demo'), sparse: join(dir, 'sparse-census') };
}

// An inventory's trees spread k times as far from the first tree.
function spread(text, k) {
  const lines = text.trim().split('\n');
  const head = lines[0].split(',');
  const [lat, lon] = [head.indexOf('latitude'), head.indexOf('longitude')];
  let origin = null;
  return [lines[0], ...lines.slice(1).map((line) => {
    const f = line.split(',');
    const y = Number(f[lat]), x = Number(f[lon]);
    if (f.length !== head.length || !Number.isFinite(y) || !Number.isFinite(x) || !f[lat] || !f[lon]) return line;
    origin ??= [y, x];
    f[lat] = (origin[0] + (y - origin[0]) * k).toFixed(8);
    f[lon] = (origin[1] + (x - origin[1]) * k).toFixed(8);
    return f.join(',');
  })].join('\n') + '\n';
}

if (import.meta.url === pathToFileURL(process.argv[1]).href) {
  const [bin, dir] = process.argv.slice(2);
  if (!bin || !dir) {
    console.error('usage: node demo-cities.mjs path/to/sylva DIR');
    process.exit(2);
  }
  writeDemoCities(bin, dir);
}
