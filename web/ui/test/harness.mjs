// What the browser tests share: their command-line options, Debian's Chromium through
// playwright-core (never a downloaded browser; exit 77, ctest's SKIP_RETURN_CODE, when either is
// missing), a watchdog, `nbar serve` started on a free port of 127.0.0.1, and `python3 -m http.server`.
import { spawn } from 'node:child_process';
import { existsSync } from 'node:fs';

export const SKIP = 77;

export const arg = (name, fallback) => { const i = process.argv.indexOf(name); return i > 0 ? process.argv[i + 1] : fallback; };

// Chromium launched headless, or the process ends with SKIP when it cannot be.
export async function launchChromium() {
  const path = arg('--chromium', process.env.CHROMIUM || '/usr/bin/chromium');
  let chromium;
  try {
    ({ chromium } = await import('playwright-core'));
  } catch {
    console.log('SKIP: playwright-core is not installed (npm ci in web/ui)');
    process.exit(SKIP);
  }
  if (!existsSync(path)) { console.log(`SKIP: no Chromium at ${path}`); process.exit(SKIP); }
  return chromium.launch({ executablePath: path, args: ['--no-sandbox', '--disable-gpu'] });
}

// Ends the process as failed after `ms`, calling `cleanup` first; returns the timer to clear.
export function watchdog(ms, cleanup = () => {}) {
  return setTimeout(() => { console.error('FAIL: over the time limit'); cleanup(); process.exit(1); }, ms);
}

// `nbar serve` on a port the system picks (its first line says which): {base, stop}. The server
// is stopped when the process exits or is interrupted; the process ends (1) when it does not start.
export async function startServer(nbar) {
  if (!existsSync(nbar)) { console.error(`no nbar program at ${nbar}`); process.exit(1); }
  const server = spawn(nbar, ['serve', '--port', '0', '--host', '127.0.0.1'], { stdio: ['ignore', 'pipe', 'pipe'] });
  const stop = () => { try { server.kill('SIGTERM'); } catch { /* gone */ } };
  process.on('exit', stop);
  for (const signal of ['SIGINT', 'SIGTERM']) process.on(signal, () => { stop(); process.exit(1); });
  const base = await new Promise((resolve, reject) => {
    let text = '';
    const timer = setTimeout(() => reject(new Error(`nbar serve did not start: ${text}`)), 10000);
    const read = (d) => {
      text += d;
      const m = /http:\/\/127\.0\.0\.1:(\d+)\//.exec(text);
      if (m) { clearTimeout(timer); resolve(`http://127.0.0.1:${m[1]}/`); }
    };
    server.stdout.on('data', read);
    server.stderr.on('data', read);
    server.on('exit', (code) => reject(new Error(`nbar serve exited (${code}): ${text}`)));
  }).catch((e) => { console.error(e.message); stop(); process.exit(1); });
  return { base, stop };
}

// `python3 -m http.server` serving `site` on a free port of 127.0.0.1: {base, log, stop}; its
// log (one line a request) is kept for the caller to check.
export async function serveStatic(site, python = 'python3') {
  const server = spawn(python, ['-u', '-m', 'http.server', '0', '--bind', '127.0.0.1', '--directory', site],
    { stdio: ['ignore', 'pipe', 'pipe'] });
  const log = [];
  server.stderr.on('data', (d) => log.push(...String(d).split('\n').filter(Boolean)));
  const stop = () => { try { server.kill('SIGTERM'); } catch { /* gone */ } };
  process.on('exit', stop);
  const base = await new Promise((resolve, reject) => {
    let text = '';
    const timer = setTimeout(() => reject(new Error(`http.server did not start: ${text}`)), 10000);
    server.stdout.on('data', (d) => {
      text += d;
      const m = /port (\d+)/.exec(text);
      if (m) { clearTimeout(timer); resolve(`http://127.0.0.1:${m[1]}/`); }
    });
    server.on('exit', (code) => reject(new Error(`http.server exited (${code}): ${text}`)));
  });
  return { base, log, stop };
}
