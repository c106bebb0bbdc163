// A picture of the viewer on an .srm file, once it has drawn the whole file:
//   node web/tools/screenshot.mjs FILE.srm OUT.png [--width W] [--height H]
// Needs web/dist (web/build.sh) and Debian's chromium.
import { existsSync, statSync } from 'node:fs';
import { basename } from 'node:path';

import { launchChromium } from './chromium.mjs';
import { startServer } from './serve.mjs';

function usage(message) {
  if (message) console.error(`screenshot.mjs: ${message}`);
  console.error('usage: screenshot.mjs FILE.srm OUT.png [--width W] [--height H]');
  process.exit(2);
}

const args = process.argv.slice(2);
const paths = [];
const size = { width: 900, height: 600 };
for (let i = 0; i < args.length; ++i) {
  if (args[i] === '--width' || args[i] === '--height') {
    const value = Number(args[++i]);
    if (!Number.isInteger(value) || value < 100 || value > 4000) usage(`${args[i - 1]} needs a whole number in 100..4000`);
    size[args[i - 1].slice(2)] = value;
  } else {
    paths.push(args[i]);
  }
}
if (paths.length !== 2) usage();
const [file, out] = paths;
if (!existsSync(file) || !statSync(file).isFile()) {
  console.error(`screenshot.mjs: ${file}: no such file`);
  process.exit(1);
}

const server = await startServer({ files: [file] });
const browser = await launchChromium();
try {
  const page = await browser.newPage({ viewport: size });
  const src = `/file/${encodeURIComponent(basename(file))}`;
  await page.goto(`http://127.0.0.1:${server.port}/viewer/?src=${src}`);
  await page.waitForFunction(() => window.srcodecViewer?.done === true, null, { timeout: 60_000 });
  const { status, message } = await page.evaluate(() => window.srcodecViewer);
  if (status !== 'done') throw new Error(`the viewer did not draw ${file}: ${message}`);
  await page.screenshot({ path: out });
  console.error(`screenshot.mjs: ${out}, ${Math.round(statSync(out).size / 1024)} kB`);
} finally {
  await browser.close();
  await server.close();
}
