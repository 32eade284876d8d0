// Many clients at once, each its own: a worker thread with its own event loop and its own
// connection to the server, opened (keep-alive) before the burst as a browser that has the
// page open holds one. All wait at one barrier and send together, so a burst times the
// server's answers, not one client thread queueing twenty requests behind one another.
// Each speaks plain HTTP/1.1 on its socket (a GET, then the answer's head and as many bytes
// as its Content-Length says): the least a client can cost, because here the twenty
// clients share the server's two cores.
//
// In the main thread: `const pool = await clients(n)`, then `await pool.burst(urls)` (one
// URL per client, fewer clients than `n` allowed) resolves to { status, first, ms, bytes }
// per URL, `first` being the time to the answer's first byte; then `await pool.close()`.

import { Worker, isMainThread, parentPort, workerData } from 'node:worker_threads';
import net from 'node:net';

if (!isMainThread) {
  const [ready, go] = [new Int32Array(workerData.ready), new Int32Array(workerData.go)];
  let socket = null;
  let waiting = null;   // the answer being read: { head, got, t0, first, ... }

  const connect = (url) => new Promise((resolve, reject) => {
    const s = net.connect(Number(url.port), url.hostname, () => resolve(s));
    s.setNoDelay(true);
    s.on('error', (e) => { if (waiting) waiting.reject(e); else reject(e); });
    s.on('close', () => { socket = null; if (waiting) waiting.reject(new Error('connection closed')); });
    s.on('data', (chunk) => waiting && waiting.take(chunk));
  });

  const get = (url) => new Promise((resolve, reject) => {
    const t0 = performance.now();
    let first = null, head = Buffer.alloc(0), status = 0, length = null, got = 0;
    waiting = {
      reject: (e) => { waiting = null; reject(e); },
      take(chunk) {
        first ??= performance.now() - t0;
        if (length === null) {
          head = Buffer.concat([head, chunk]);
          const end = head.indexOf('\r\n\r\n');
          if (end < 0) return;
          const lines = head.subarray(0, end).toString('latin1').split('\r\n');
          status = Number(lines[0].split(' ')[1]);
          const cl = lines.find((l) => /^content-length:/i.test(l));
          if (!cl) { this.reject(new Error(`${url}: an answer without Content-Length`)); return; }
          length = Number(cl.split(':')[1]);
          chunk = head.subarray(end + 4);
        }
        got += chunk.length;
        if (got >= length) {
          waiting = null;
          resolve({ status, first, ms: performance.now() - t0, bytes: got });
        }
      },
    };
    socket.write(`GET ${url.pathname}${url.search} HTTP/1.1\r\nHost: ${url.host}\r\n\r\n`);
  });

  parentPort.on('message', async ({ warm, url, round }) => {
    // Open (or keep) this client's connection, then wait for every other client.
    const target = new URL(url);
    socket ??= await connect(target);
    await get(new URL(warm));
    Atomics.add(ready, 0, 1);
    Atomics.notify(ready, 0);
    Atomics.wait(go, 0, round - 1);
    parentPort.postMessage(await get(target));
  });
}

export async function clients(n) {
  const ready = new SharedArrayBuffer(4);
  const go = new SharedArrayBuffer(4);
  const workers = Array.from({ length: n }, () =>
    new Worker(new URL(import.meta.url), { workerData: { ready, go } }));
  let round = 0;
  return {
    // Each URL to one client; resolves once every answer is read. `warm` is a cheap URL
    // each client asks first, on the connection it then uses.
    async burst(urls, warm) {
      round++;
      Atomics.store(new Int32Array(ready), 0, 0);
      const answers = urls.map((url, i) => new Promise((resolve, reject) => {
        const w = workers[i];
        const failed = (e) => { w.off('message', answered); reject(e); };
        const answered = (m) => { w.off('error', failed); resolve(m); };
        w.once('message', answered);
        w.once('error', failed);
        w.postMessage({ warm, url, round });
      }));
      const count = new Int32Array(ready);
      const end = Date.now() + 20000;
      while (Atomics.load(count, 0) < urls.length) {
        if (Date.now() > end) throw new Error('clients not ready in 20 s');
        await new Promise((ok) => setTimeout(ok, 2));
      }
      Atomics.store(new Int32Array(go), 0, round);
      Atomics.notify(new Int32Array(go), 0);
      return Promise.all(answers);
    },
    close: () => Promise.all(workers.map((w) => w.terminate())),
  };
}
