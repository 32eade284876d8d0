// A city as a new user first sees it: `sylva serve --city CITY`, the city view at its default
// view, a screenshot, what it drew, how many trees lie in the picture, a click on a marker,
// frames a second turning; the same 300 m from the middle (the opening view before issue X
// fitted it); then zoomed in at the middle, another screenshot.
//
//   node look.mjs path/to/sylva CITY SHOTS NAME
import { chromium } from 'playwright-core';
import { writeFileSync } from 'node:fs';
import { startServer, waitUntil, check } from './common.mjs';

const [bin, city, shots, label] = process.argv.slice(2);
const name = city.split('/').filter(Boolean).pop();
const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
  args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist'],
});
const server = await startServer(bin, ['--city', city]);
try {
  const page = await browser.newPage({ viewport: { width: 1600, height: 1000 } });
  page.on('pageerror', (e) => console.log(`page error: ${e.message}`));
  await page.goto(`${server.url}city.html?city=${encodeURIComponent(name)}`);
  const first = await waitUntil('the first trees', () => page.evaluate(() => window.sylvaCity?.firstTreesMs), 120);
  await waitUntil('the epoch', () => page.evaluate(() => window.sylvaCity.shownEpoch != null), 300);
  const all = await page.evaluate(() => window.sylvaCity.shownMs);
  console.log(`first trees ${first.toFixed(0)} ms; every tile of the default view ${all.toFixed(0)} ms`);
  await new Promise((ok) => setTimeout(ok, 500));
  writeFileSync(`${shots}/${label}-default.png`, await page.screenshot());
  console.log('drawn', JSON.stringify(await page.evaluate(() => window.sylvaCity.drawn())));
  console.log('fitted', JSON.stringify(await page.evaluate(() => window.sylvaCity.fitted)));
  console.log('in picture', JSON.stringify(await page.evaluate(() => window.sylvaCity.treesInPicture?.())));
  const turn = await page.evaluate(() => window.sylvaCity.turn(4000));
  console.log(`turning: ${((1000 * turn.frames) / turn.ms).toFixed(1)} fps`);
  const points = await page.evaluate(() => window.sylvaCity.markerPoints?.(10) || []);
  for (const p of points.slice(0, 3)) {
    const before = await page.evaluate(() => window.sylvaCity.clicks.length);
    await page.mouse.click(p.x, p.y);
    const click = await waitUntil('click', () => page.evaluate((n) => window.sylvaCity.clicks[n], before), 10);
    console.log(`marker of tree ${p.id} clicked: card of ${click.id} in ${click.ms.toFixed(1)} ms`);
  }
  writeFileSync(`${shots}/${label}-card.png`, await page.screenshot());
  // The opening view before it was fitted: 300 m from the middle.
  if (await page.evaluate(() => !!window.sylvaCity.lookFrom)) {
    await page.evaluate(() => document.getElementById('card').hidden = true);
    await page.evaluate(() => { window.sylvaCity.shownEpoch = null; window.sylvaCity.lookFrom(300); });
    await new Promise((ok) => setTimeout(ok, 1500));
    await waitUntil('the tiles at 300 m', () => page.evaluate(() => window.sylvaCity.shownEpoch != null), 300);
    writeFileSync(`${shots}/${label}-300m.png`, await page.screenshot());
    console.log('at 300 m drawn', JSON.stringify(await page.evaluate(() => window.sylvaCity.drawn())));
    const near = await page.evaluate(() => window.sylvaCity.turn(4000));
    console.log(`turning at 300 m: ${((1000 * near.frames) / near.ms).toFixed(1)} fps`);
  }
  await page.evaluate(() => document.getElementById('card').hidden = true);
  // Zoomed in: the camera moved to a fifth of its distance toward the middle.
  await page.mouse.move(800, 500);
  for (let i = 0; i < 12; i++) { await page.mouse.wheel(0, -300); await new Promise((ok) => setTimeout(ok, 60)); }
  await new Promise((ok) => setTimeout(ok, 3000));
  await waitUntil('tiles', () => page.evaluate(() => window.sylvaCity.shownEpoch != null), 120).catch(() => {});
  writeFileSync(`${shots}/${label}-zoomed.png`, await page.screenshot());
  console.log('zoomed drawn', JSON.stringify(await page.evaluate(() => window.sylvaCity.drawn())));
} finally {
  await server.stop();
  await browser.close();
}
