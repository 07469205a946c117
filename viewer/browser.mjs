// Shared by the browser tests and screenshot.mjs: start a tcbench server and
// read its address, and launch Debian's chromium headless with WebGL in
// software (SwiftShader) through playwright-core.
import { spawn } from 'node:child_process';
import { existsSync } from 'node:fs';
import { chromium } from 'playwright-core';

export function startServer(binary, args) {
  const child = spawn(binary, args, { stdio: ['ignore', 'pipe', 'pipe'] });
  let out = '';
  let err = '';
  child.stderr.on('data', (d) => { err += d; });
  const url = new Promise((resolve, reject) => {
    child.stdout.on('data', (d) => {
      out += d;
      const m = out.match(/http:\/\/127\.0\.0\.1:\d+\//);
      if (m) resolve(m[0]);
    });
    child.on('exit', (code) => reject(new Error(`tcbench exited ${code} before listening: ${err}`)));
  });
  const exited = new Promise((resolve) => child.on('exit', (code, signal) => resolve({ code, signal, out: () => out, err: () => err })));
  return { child, url, exited };
}

export async function launchBrowser() {
  const executablePath = process.env.TCBENCH_CHROMIUM ?? '/usr/bin/chromium';
  if (!existsSync(executablePath)) return { skip: `no browser at ${executablePath}` };
  try {
    const browser = await chromium.launch({
      executablePath,
      headless: true,
      args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--disable-quic', '--no-first-run',
        '--disable-background-networking', '--disable-component-update', '--disable-sync'],
    });
    return { browser };
  } catch (e) {
    return { skip: `chromium did not start: ${e.message.split('\n')[0]}` };
  }
}
