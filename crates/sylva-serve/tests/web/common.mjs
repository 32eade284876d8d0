// What the browser test and the load test share: starting `sylva serve` on a free port of
// 127.0.0.1 and stopping it, and timing a request.

import { spawn } from 'node:child_process';

// Starts the server binary `bin` and resolves to { url, stop } once it says where it listens.
export function startServer(bin, extra = []) {
  return new Promise((resolve, reject) => {
    const child = spawn(bin, ['serve', '--port', '0', '--host', '127.0.0.1', ...extra], {
      stdio: ['ignore', 'pipe', 'inherit'],
    });
    let said = '';
    const timer = setTimeout(() => { child.kill(); reject(new Error(`no address from ${bin} in 20 s`)); }, 20000);
    child.on('exit', (code) => reject(new Error(`${bin} serve ended with ${code}: ${said}`)));
    child.stdout.on('data', (chunk) => {
      said += chunk;
      const m = said.match(/http:\/\/127\.0\.0\.1:\d+\//);
      if (m) {
        clearTimeout(timer);
        resolve({
          url: m[0],
          pid: child.pid,
          stop: () => new Promise((done) => { child.removeAllListeners('exit'); child.on('exit', done); child.kill('SIGINT'); }),
        });
      }
    });
  });
}

// GETs `url`, reads the whole body, and resolves to { status, ms, first, bytes }: `ms` until
// the whole body is read, `first` until the server's answer began (its headers), which is
// the server's own time, apart from how fast this one client thread reads many bodies.
export async function timed(url) {
  const t0 = performance.now();
  const r = await fetch(url);
  const first = performance.now() - t0;
  const body = await r.arrayBuffer();
  return { status: r.status, ms: performance.now() - t0, first, bytes: body.byteLength };
}

export async function waitUntil(what, test, seconds) {
  const end = Date.now() + seconds * 1000;
  for (;;) {
    const value = await test();
    if (value) return value;
    if (Date.now() > end) throw new Error(`timed out after ${seconds} s waiting for ${what}`);
    await new Promise((ok) => setTimeout(ok, 50));
  }
}

export function check(ok, message) {
  if (!ok) throw new Error(`FAILED: ${message}`);
  console.log(`ok: ${message}`);
}
