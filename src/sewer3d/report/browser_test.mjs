// The report's browser test (docs/report.md), driven over the Chrome DevTools protocol through
// Chromium's --remote-debugging-pipe (NUL-separated JSON on file descriptors 3 and 4): no
// WebSocket, no port, no npm package; any Node from 18 on.
// usage: node browser_test.mjs CHROMIUM INDEX_HTML EXPECTED_JSON SHOT_PNG
// Checks: no console errors, exceptions or network requests; the viewer's pixels show a
// textured pipe; a real mouse click on the red disc of the known bump reads its station within
// 5 mm, its clock within 0.25 h and its radius within 0.5 mm.
import { spawn } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { pathToFileURL } from 'node:url';
import { decodePng } from './png_decode.mjs';

const [chromiumPath, indexHtml, expectedJson, shotPath] = process.argv.slice(2);
const expected = JSON.parse(readFileSync(expectedJson, 'utf8'));
const profile = mkdtempSync(join(tmpdir(), 'sewer3d-chromium-'));
const failures = [];
const t0 = Date.now();
const check = (ok, text) => {
  console.log(`${ok ? 'ok   ' : 'FAIL '}${text} [${((Date.now() - t0) / 1000).toFixed(1)} s]`);
  if (!ok) failures.push(text);
};

const chromium = spawn(chromiumPath, ['--headless=new', '--no-sandbox', '--disable-gpu-sandbox',
  '--enable-unsafe-swiftshader', '--use-angle=swiftshader', '--remote-debugging-pipe',
  `--user-data-dir=${profile}`, '--no-first-run', '--window-size=1280,900', 'about:blank'],
{ stdio: ['ignore', 'ignore', 'pipe', 'pipe', 'pipe'] });
let chromiumLog = '';
chromium.stderr.on('data', (d) => { chromiumLog += d; });
const timer = setTimeout(() => { console.log('FAIL timed out\n' + chromiumLog.slice(-2000)); finish(1); }, 60000);

// Ends Chromium, waits for it to go (it writes its profile until then), removes the profile.
async function finish(code) {
  clearTimeout(timer);
  if (chromium.exitCode === null) {
    const gone = new Promise((resolve) => chromium.once('exit', resolve));
    chromium.kill();
    await Promise.race([gone, new Promise((resolve) => setTimeout(resolve, 5000))]);
  }
  // Chromium's helper processes may outlive it for a moment and still write there: a profile
  // that cannot be removed yet is left in the temporary folder, not a failed test.
  try {
    rmSync(profile, { recursive: true, force: true, maxRetries: 10, retryDelay: 200 });
  } catch (e) {
    console.log(`note: the Chromium profile ${profile} is left behind (${e.code})`);
  }
  process.exit(code);
}

let nextId = 1, session;
const pending = new Map(), listeners = [];
let buffered = '';
chromium.stdio[4].on('data', (chunk) => {
  const parts = (buffered + chunk.toString('utf8')).split('\0');
  buffered = parts.pop();
  for (const part of parts) {
    const message = JSON.parse(part);
    if (message.id && pending.has(message.id)) {
      const { resolve, reject } = pending.get(message.id);
      pending.delete(message.id);
      if (message.error) reject(new Error(JSON.stringify(message.error))); else resolve(message.result);
    } else if (message.method) {
      listeners.forEach((l) => l(message));
    }
  }
});
// A command to the browser, or to the page once attached (flat sessions).
const send = (method, params = {}, toBrowser = false) => new Promise((resolve, reject) => {
  const id = nextId++;
  pending.set(id, { resolve, reject });
  const message = { id, method, params };
  if (!toBrowser) message.sessionId = session;
  chromium.stdio[3].write(JSON.stringify(message) + '\0');
});
const evaluate = async (expression) =>
  (await send('Runtime.evaluate', { expression, awaitPromise: true, returnByValue: true })).result.value;

const problems = [];
let loaded = null;
const loadedPromise = new Promise((resolve) => { loaded = resolve; });
listeners.push(({ method, params }) => {
  if (method === 'Runtime.exceptionThrown') problems.push('exception: ' + params.exceptionDetails.text + ' ' + (params.exceptionDetails.exception?.description ?? ''));
  if (method === 'Runtime.consoleAPICalled' && ['error', 'assert'].includes(params.type))
    problems.push('console.error: ' + params.args.map((a) => a.value ?? a.description).join(' '));
  if (method === 'Log.entryAdded' && params.entry.level === 'error') problems.push('log: ' + params.entry.text);
  if (method === 'Network.requestWillBeSent' && !/^(data|file|blob):/.test(params.request.url))
    problems.push('network request: ' + params.request.url);
  if (method === 'Page.loadEventFired') loaded();
});

try {
  const { targetInfos } = await send('Target.getTargets', {}, true);
  const page = targetInfos.find((t) => t.type === 'page');
  session = (await send('Target.attachToTarget', { targetId: page.targetId, flatten: true }, true)).sessionId;
  for (const domain of ['Runtime', 'Log', 'Page', 'Network']) await send(`${domain}.enable`);
  await send('Emulation.setDeviceMetricsOverride', { width: 1280, height: 900, deviceScaleFactor: 1, mobile: false });
  await send('Page.navigate', { url: pathToFileURL(indexHtml).href });
  await loadedPromise;
  if (!expected.viewer) throw new Error('this build has no 3D viewer: npm was unavailable when it was configured');
  const ready = await evaluate(`new Promise((resolve) => { const t0 = Date.now(); (function poll() {
    if (window.sewer3dViewer && window.sewer3dViewer.ready) resolve(true);
    else if (Date.now() - t0 > 20000) resolve(false); else setTimeout(poll, 50); })(); })`);
  check(ready === true, 'the viewer started (window.sewer3dViewer.ready)');
  const rect = await evaluate(`(async () => { const c = document.getElementById('viewer-canvas');
    c.scrollIntoView({ block: 'center' });
    await new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r)));
    const b = c.getBoundingClientRect(); return { x: b.x, y: b.y, width: b.width, height: b.height }; })()`);
  const shot = Buffer.from((await send('Page.captureScreenshot', { format: 'png' })).data, 'base64');
  writeFileSync(shotPath, shot);
  console.log(`screenshot: ${shotPath}`);
  const image = decodePng(shot);
  let pipe = 0, total = 0, red = 0, redX = 0, redY = 0, sum = 0, sumSq = 0;
  for (let y = Math.ceil(rect.y); y < Math.floor(rect.y + rect.height); ++y) {
    for (let x = Math.ceil(rect.x); x < Math.floor(rect.x + rect.width); ++x) {
      const k = (y * image.width + x) * image.channels;
      const [r, g, b] = [image.data[k], image.data[k + 1], image.data[k + 2]];
      ++total;
      if (Math.abs(r - 0x1b) + Math.abs(g - 0x1f) + Math.abs(b - 0x24) > 40) {
        ++pipe;
        sum += g;
        sumSq += g * g;
      }
      if (r > 120 && r > 2 * g && r > 2 * b) { ++red; redX += x; redY += y; }
    }
  }
  const share = pipe / Math.max(total, 1);
  const spread = pipe ? Math.sqrt(sumSq / pipe - (sum / pipe) ** 2) : 0;
  check(share > 0.15, `pipe pixels ${(100 * share).toFixed(1)} % of the viewer (> 15 %)`);
  check(spread > 8, `texture visible on the pipe: green spread ${spread.toFixed(1)} (> 8)`);
  check(red >= 20, `red disc of the known bump seen: ${red} px (>= 20)`);
  if (red >= 20) {
    const x = redX / red, y = redY / red;
    for (const type of ['mouseMoved', 'mousePressed', 'mouseReleased'])
      await send('Input.dispatchMouseEvent', { type, x, y, button: 'left', buttons: type === 'mousePressed' ? 1 : 0, clickCount: 1 });
    const read = await evaluate(`(() => { const d = document.getElementById('viewer-readout');
      return { station: Number(d.dataset.stationMm), clock: Number(d.dataset.clockH), radius: Number(d.dataset.radiusMm), text: d.textContent }; })()`);
    console.log(`click at (${x.toFixed(1)}, ${y.toFixed(1)}) px: ${read.text}`);
    const after = (await send('Page.captureScreenshot', { format: 'png' })).data;
    writeFileSync(shotPath.replace(/\.png$/, '_click.png'), Buffer.from(after, 'base64'));
    check(Math.abs(read.station - expected.station_mm) <= 5, `station ${read.station} mm, expected ${expected.station_mm} ± 5`);
    check(Math.abs(read.clock - expected.clock_h) <= 0.25, `clock ${read.clock} h, expected ${expected.clock_h} ± 0.25`);
    check(Math.abs(read.radius - expected.radius_mm) <= 0.5, `radius ${read.radius} mm, expected ${expected.radius_mm} ± 0.5`);
  }
  check(problems.length === 0, `no console errors, exceptions or network requests${problems.length ? ': ' + problems.join('; ') : ''}`);
} catch (error) {
  check(false, String(error.stack || error));
}
await finish(failures.length ? 1 : 0);
