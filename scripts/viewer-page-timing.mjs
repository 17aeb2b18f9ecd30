// Loads a viewer page in a running Chromium (--remote-debugging-port) through the DevTools
// protocol, in real time, and prints what the page measured as JSON: data-ready-ms (navigation
// to first frame) and window.contactlabBench (the #bench=orbit frame times, src/view/web/viewer/orbit_bench.js).
// Usage: node --experimental-websocket scripts/viewer-page-timing.mjs PORT URL [TIMEOUT_S]
// (scripts/bench-viewer-page.sh runs it).
const [port, url, timeoutArg] = process.argv.slice(2);
const deadline = Date.now() + 1000 * Number(timeoutArg || 90);
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

async function pageSocket() {
  for (;;) {
    try {
      const targets = await (await fetch(`http://127.0.0.1:${port}/json/list`)).json();
      const page = targets.find((t) => t.type === 'page');
      if (page) return page.webSocketDebuggerUrl;
    } catch (e) { /* not listening yet */ }
    if (Date.now() > deadline) throw new Error(`no page target on port ${port}`);
    await sleep(100);
  }
}

const ws = new WebSocket(await pageSocket());
await new Promise((resolve, reject) => { ws.onopen = resolve; ws.onerror = reject; });
let nextId = 1;
const pending = new Map();
ws.onmessage = (e) => {
  const m = JSON.parse(e.data);
  if (m.id && pending.has(m.id)) { pending.get(m.id)(m); pending.delete(m.id); }
};
const send = (method, params) => new Promise((resolve) => {
  const id = nextId++;
  pending.set(id, resolve);
  ws.send(JSON.stringify({id, method, params}));
});

await send('Page.navigate', {url});
const probe = `JSON.stringify({ready_ms: Number(document.documentElement.getAttribute('data-ready-ms')) || null,
  errors: Number(document.documentElement.getAttribute('data-errors')), bench: window.contactlabBench || null})`;
let result = null;
while (Date.now() < deadline) {
  const r = await send('Runtime.evaluate', {expression: probe, returnByValue: true});
  const value = r.result && r.result.result ? r.result.result.value : undefined;
  result = typeof value === 'string' ? JSON.parse(value) : result;  // not yet during navigation
  if (result && result.bench) break;
  await sleep(250);
}
console.log(JSON.stringify(result));
ws.close();
process.exit(result && result.bench ? 0 : 1);
