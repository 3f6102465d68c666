// Draws the scenes of scenes.json from a baked file in headless Chromium (WebGL2 on SwiftShader)
// with JadeTranslucentMaterial and with MeshPhysicalMaterial, writes PNGs, and times the Jade
// material against MeshStandardMaterial. tests/test_web.cpp runs it and compares the PNGs with
// jade render's.
//   node web/test/render_scenes.mjs --glb FILE --out DIR [--frames N] [--light-path auto|vertex|fragment]
//                                   [--no-shadows]
//   node web/test/render_scenes.mjs --glb FILE --screenshot FILE
// Writes DIR/web_<scene>_jade.png, DIR/web_<scene>_physical.png, without --no-shadows
// DIR/web_<scene>_unshadowed.png (Jade's material with shadows off), and with --frames > 0
// (default 30) DIR/web_timing.json.
// --screenshot instead opens the demo page (index.html) and saves what it shows.
// The browser: $JADE_CHROMIUM, else /usr/bin/chromium-headless-shell (Debian's package).
import { existsSync, mkdirSync, readFileSync, renameSync, writeFileSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import puppeteer from 'puppeteer-core';
import { startServer } from '../serve.js';

const here = dirname(fileURLToPath(import.meta.url));
const args = process.argv.slice(2);
const option = (name, fallback) => { const i = args.indexOf(name); return i >= 0 ? args[i + 1] : fallback; };
const glb = option('--glb'), out = option('--out'), frames = Number(option('--frames', '30'));
const screenshot = option('--screenshot');
const lightPath = option('--light-path', 'auto');
if (!glb || (!out && !screenshot)) {
  console.error('usage: node web/test/render_scenes.mjs --glb FILE (--out DIR [--frames N] | --screenshot FILE)');
  process.exit(2);
}
const browserPath = process.env.JADE_CHROMIUM || '/usr/bin/chromium-headless-shell';
if (!existsSync(browserPath)) {
  console.error(`render_scenes: no browser at ${browserPath} (install Debian's chromium-headless-shell: ` +
                'bash third_party/install_deps.sh, or set JADE_CHROMIUM)');
  process.exit(1);
}
if (!existsSync(glb)) { console.error(`render_scenes: ${glb}: no such file`); process.exit(1); }

// The demo page opens the committed file by default; another one is served as /baked.glb.
const glbIsDemo = resolve(glb) === resolve(here, '..', 'assets', 'bunny_blue_jewel.glb');
const writeAtomic = (path, data) => { writeFileSync(path + '.tmp', data); renameSync(path + '.tmp', path); };
const server = await startServer({ extra: { '/baked.glb': resolve(glb) } });
const browser = await puppeteer.launch({
  executablePath: browserPath,
  headless: 'shell',
  args: ['--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--no-sandbox', '--disable-gpu-sandbox',
         '--no-first-run', '--disable-extensions'],
});
let failed = false;
const problems = [];
try {
  const page = await browser.newPage();
  page.on('console', (m) => { if (m.type() === 'error' || m.type() === 'warn') problems.push(`${m.type()}: ${m.text()}`); });
  page.on('pageerror', (e) => problems.push(`page error: ${e.message}`));
  if (screenshot) {
    await page.setViewport({ width: 960, height: 600 });
    await page.goto(`${server.url}index.html${glbIsDemo ? '' : '?file=/baked.glb'}`, { waitUntil: 'load' });
    await page.waitForFunction('window.jadeDemoReady === true', { timeout: 60000 });
    await page.screenshot({ path: screenshot + '.tmp.png' });
    renameSync(screenshot + '.tmp.png', screenshot);
    console.log(`wrote ${screenshot}`);
  } else {
    mkdirSync(out, { recursive: true });
    const config = JSON.parse(readFileSync(join(here, 'scenes.json'), 'utf8'));
    await page.goto(`${server.url}test/scenes.html`, { waitUntil: 'load' });
    await page.waitForFunction('window.jadeTestReady === true', { timeout: 30000 });
    const loaded = await page.evaluate((url, where, shadows) => window.jadeTest.load(url, where, shadows), '/baked.glb',
                                       lightPath, !args.includes('--no-shadows'));
    console.log(`${glb}: ${loaded.join('; ')}`);
    const info = await page.evaluate(() => window.jadeTest.info());
    console.log(`browser: ${await browser.version()}, WebGL: ${info.renderer}, MSAA ${info.samples}, three r${info.three}`);
    const timing = { frames, size: config.size, renderer: info.renderer, scenes: {} };
    for (const [name, lights] of Object.entries(config.scenes)) {
      const options = { camera: config.camera, lights, size: config.size };
      const shadows = !args.includes('--no-shadows');
      for (const material of shadows ? ['jade', 'physical', 'unshadowed'] : ['jade', 'physical']) {
        const url = await page.evaluate((o) => window.jadeTest.render(o), { ...options, material });
        const file = join(out, `web_${name}_${material}.png`);
        writeAtomic(file, Buffer.from(url.slice(url.indexOf(',') + 1), 'base64'));
        console.log(`wrote ${file}`);
      }
      if (!(frames > 0)) continue;
      const [jade, standard] = await page.evaluate((o, n) => window.jadeTest.time(o, ['jade', 'standard'], n),
                                                   options, frames);
      timing.scenes[name] = { jade_ms: jade, standard_ms: standard, ratio: jade / standard };
      console.log(`frame time (${name}, ${config.size.join('x')}, median of ${frames} frames): JadeTranslucentMaterial ` +
                  `${jade.toFixed(2)} ms, MeshStandardMaterial ${standard.toFixed(2)} ms, ratio ${(jade / standard).toFixed(2)}`);
    }
    if (frames > 0) writeAtomic(join(out, 'web_timing.json'), JSON.stringify(timing, null, 2) + '\n');
  }
  if (problems.length > 0) {
    console.error(`render_scenes: the page reported:\n  ${problems.join('\n  ')}`);
    failed = true;
  }
} catch (error) {
  console.error(`render_scenes: ${error.stack ?? error}`);
  if (problems.length > 0) console.error(`render_scenes: the page reported:\n  ${problems.join('\n  ')}`);
  failed = true;
} finally {
  await browser.close();
  await server.close();
}
process.exit(failed ? 1 : 0);
