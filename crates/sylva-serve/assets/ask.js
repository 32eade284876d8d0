// Asking the server, for both pages. A 503 is not a failure: the server grows as many species
// at once as its cores and memory bound allow, and answers a request that has waited its limit
// (30 s by default) with 503, how many growths it waits for (`growing`) and when to ask again
// (`Retry-After`), while the growth goes on. So each page says what it waits for and asks again,
// rather than failing or seeming to hang.

// The first answer that is not a 503; `waiting(n)` is told each time the server is busy with
// n growths, before the wait.
export async function ask(url, waiting) {
  for (;;) {
    const r = await fetch(url);
    if (r.status !== 503) return r;
    const body = await r.json().catch(() => ({}));
    waiting?.(body.growing ?? 1);
    const seconds = Number(r.headers.get('retry-after')) || body.retry_after || 1;
    await new Promise((ok) => setTimeout(ok, 1000 * seconds));
  }
}

// A JSON answer, or an error carrying the server's message.
export async function askJson(url, waiting) {
  const r = await ask(url, waiting);
  const body = await r.json().catch(() => null);
  if (!r.ok || body == null) throw new Error(body?.error || `${url}: ${r.status}`);
  return body;
}

// What a page shows while it waits.
export function waitingText(n) {
  return `Waiting for ${n} growth${n === 1 ? '' : 's'} on the server…`;
}
