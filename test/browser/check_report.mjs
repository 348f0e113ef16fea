// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Opens an HTML report of soup_topology in headless Chromium (software GL) from file:// and checks it:
//   node check_report.mjs --page REPORT.html [--json REPORT.json] [--screenshot OUT.png]
//                         [--red yes|no] [--markers yes] [--max-seconds S] [--chromium PATH]
// Fails (exit code 1) on a console error or an uncaught exception, on any request other than the
// page itself, when <body data-ready="true"> is not reached within S seconds (default 10), on a
// blank view, when red pixels (border edges) are seen with --red no or missed with --red yes,
// when the element `report-json` is not the object of the --json file, when a click on the first
// listed ambiguous site (or, without one, the first listed hole) does not move the view, and on
// the markers: a kind counted without positions, a kind whose switch does not change the view when
// turned off, or, with --markers yes, no kind counted at all. Prints one line per check.

import { createRequire } from 'node:module';
import { mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { isDeepStrictEqual } from 'node:util';
import { inflateSync } from 'node:zlib';

// playwright-core is installed by `npm ci` in viewer/ (pinned in viewer/package.json).
const viewer_folder = resolve(fileURLToPath(new URL('.', import.meta.url)), '../../viewer');
const { chromium } = createRequire(join(viewer_folder, 'package.json'))('playwright-core');

function parse_arguments(argv) {
  const options = { maxSeconds: 10, chromium: '/usr/bin/chromium' };
  for (let i = 0; i < argv.length; ++i) {
    const value = () => {
      if (i + 1 >= argv.length) throw new Error(`${argv[i]} needs a value`);
      return argv[++i];
    };
    switch (argv[i]) {
      case '--page': options.page = value(); break;
      case '--json': options.json = value(); break;
      case '--screenshot': options.screenshot = value(); break;
      case '--red': options.red = value(); break;
      case '--markers': options.markers = value(); break;
      case '--max-seconds': options.maxSeconds = Number(value()); break;
      case '--chromium': options.chromium = value(); break;
      default: throw new Error(`unknown argument '${argv[i]}'`);
    }
  }
  if (!options.page) throw new Error('--page REPORT.html is needed');
  if (options.red && options.red !== 'yes' && options.red !== 'no') throw new Error('--red takes yes or no');
  if (options.markers && options.markers !== 'yes') throw new Error('--markers takes yes');
  return options;
}

// The RGBA pixels of an 8-bit, non-interlaced PNG (RGB or RGBA), as Chromium writes screenshots.
function decode_png(buffer) {
  let offset = 8;
  let width = 0, height = 0, channels = 0;
  const data = [];
  while (offset < buffer.length) {
    const length = buffer.readUInt32BE(offset);
    const type = buffer.toString('ascii', offset + 4, offset + 8);
    const body = buffer.subarray(offset + 8, offset + 8 + length);
    if (type === 'IHDR') {
      width = body.readUInt32BE(0);
      height = body.readUInt32BE(4);
      const depth = body[8], color = body[9], interlace = body[12];
      if (depth !== 8 || interlace !== 0 || (color !== 2 && color !== 6)) throw new Error('unsupported PNG');
      channels = color === 6 ? 4 : 3;
    } else if (type === 'IDAT') data.push(body);
    else if (type === 'IEND') break;
    offset += 12 + length;
  }
  const raw = inflateSync(Buffer.concat(data));
  const stride = width * channels;
  const pixels = Buffer.alloc(width * height * 4);
  const previous = Buffer.alloc(stride), current = Buffer.alloc(stride);
  for (let y = 0; y < height; ++y) {
    const filter = raw[y * (stride + 1)];
    raw.copy(current, 0, y * (stride + 1) + 1, (y + 1) * (stride + 1));
    for (let x = 0; x < stride; ++x) {
      const a = x >= channels ? current[x - channels] : 0;
      const b = previous[x];
      const c = x >= channels ? previous[x - channels] : 0;
      let predictor = 0;
      if (filter === 1) predictor = a;
      else if (filter === 2) predictor = b;
      else if (filter === 3) predictor = (a + b) >> 1;
      else if (filter === 4) {
        const p = a + b - c, pa = Math.abs(p - a), pb = Math.abs(p - b), pc = Math.abs(p - c);
        predictor = pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
      }
      current[x] = (current[x] + predictor) & 255;
    }
    for (let x = 0; x < width; ++x) {
      const o = (y * width + x) * 4;
      pixels[o] = current[x * channels];
      pixels[o + 1] = current[x * channels + 1];
      pixels[o + 2] = current[x * channels + 2];
      pixels[o + 3] = channels === 4 ? current[x * channels + 3] : 255;
    }
    current.copy(previous);
  }
  return { width, height, pixels };
}

// Counts, inside `box`, the red pixels and the pixels that differ from the most frequent colour.
function analyse_pixels(image, box) {
  const counts = new Map();
  let red = 0, total = 0;
  const x0 = Math.max(0, Math.floor(box.x)), y0 = Math.max(0, Math.floor(box.y));
  const x1 = Math.min(image.width, Math.floor(box.x + box.width)), y1 = Math.min(image.height, Math.floor(box.y + box.height));
  for (let y = y0; y < y1; ++y) {
    for (let x = x0; x < x1; ++x) {
      const o = (y * image.width + x) * 4;
      const r = image.pixels[o], g = image.pixels[o + 1], b = image.pixels[o + 2];
      if (r >= 200 && g <= 70 && b <= 70) ++red;
      const key = (r << 16) | (g << 8) | b;
      counts.set(key, (counts.get(key) || 0) + 1);
      ++total;
    }
  }
  const background = Math.max(...counts.values());
  return { red, total, drawn: total - background, colours: counts.size };
}

// The number of pixels inside `box` that differ between two images of the same size.
function count_changed_pixels(a, b, box) {
  let changed = 0;
  const x0 = Math.max(0, Math.floor(box.x)), y0 = Math.max(0, Math.floor(box.y));
  const x1 = Math.min(a.width, Math.floor(box.x + box.width)), y1 = Math.min(a.height, Math.floor(box.y + box.height));
  for (let y = y0; y < y1; ++y) {
    for (let x = x0; x < x1; ++x) {
      const o = (y * a.width + x) * 4;
      if (a.pixels[o] !== b.pixels[o] || a.pixels[o + 1] !== b.pixels[o + 1] || a.pixels[o + 2] !== b.pixels[o + 2]) ++changed;
    }
  }
  return changed;
}

// The marker kinds: every kind counted has positions on the page, and turning off the kind with
// the most positions changes the view (and turning it on again restores it).
async function check_markers(page, box, image) {
  const kinds = await page.evaluate(() => {
    const data = JSON.parse(document.getElementById('viewer-data').textContent);
    return Object.keys(data.marker_counts).map((key) => ({
      key, count: data.marker_counts[key], shown: (data.markers[key] || []).length,
    }));
  });
  const counted = kinds.filter((k) => k.count > 0);
  console.log(`     markers: ${kinds.map((k) => `${k.key} ${k.count} (${k.shown} places)`).join(', ')}`);
  if (options.markers === 'yes') check(counted.length > 0, `marker kinds counted: ${counted.length}`);
  const unplaced = counted.filter((k) => k.shown === 0).map((k) => k.key);
  check(unplaced.length === 0, `every kind counted has positions${unplaced.length ? ': missing for ' + unplaced.join(', ') : ''}`);
  if (counted.length === 0) return;
  const most = kinds.reduce((a, b) => (b.shown > a.shown ? b : a));
  const box_input = `input[type="checkbox"][data-kind="${most.key}"]`;
  await page.click(box_input);
  await page.waitForTimeout(400);
  const off = decode_png(await page.screenshot({ type: 'png' }));
  const changed = count_changed_pixels(image, off, box);
  check(changed > 0, `turning off the ${most.key} markers changes the view (${changed} pixels)`);
  await page.click(box_input);
  await page.waitForTimeout(400);
  const on = decode_png(await page.screenshot({ type: 'png' }));
  check(count_changed_pixels(image, on, box) === 0, `turning them on again restores the view`);
}

const options = parse_arguments(process.argv.slice(2));
const failures = [];
const check = (ok, what) => {
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`);
  if (!ok) failures.push(what);
};

const page_url = pathToFileURL(resolve(options.page)).href;
const profile = mkdtempSync(join(tmpdir(), 'soup-topology-chromium-'));
let context;
try {
  context = await chromium.launchPersistentContext(profile, {
    executablePath: options.chromium,
    headless: true,
    viewport: { width: 1280, height: 800 },
    args: ['--headless', '--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader',
      '--disable-background-networking', '--disable-component-update', '--disable-sync', '--no-first-run'],
  });
  const page = context.pages()[0] || await context.newPage();
  const console_errors = [];
  const requests = [];
  page.on('console', (message) => { if (message.type() === 'error') console_errors.push(message.text()); });
  page.on('pageerror', (error) => console_errors.push(String(error)));
  context.on('request', (request) => { if (request.url() !== page_url) requests.push(request.url()); });

  const start = Date.now();
  await page.goto(page_url, { waitUntil: 'commit', timeout: options.maxSeconds * 1000 });
  let ready = true;
  try {
    await page.waitForSelector('body[data-ready="true"]', { timeout: Math.max(1, options.maxSeconds * 1000 - (Date.now() - start)) });
  } catch (error) {
    ready = false;
  }
  const seconds = (Date.now() - start) / 1000;
  check(ready, `data-ready reached in ${seconds.toFixed(2)} s (limit ${options.maxSeconds} s)`);
  const viewer_built = await page.evaluate(() => document.querySelector('.not-built') === null);
  check(viewer_built, 'the page holds the 3D viewer');

  const screenshot = await page.screenshot({ type: 'png' });
  if (options.screenshot) writeFileSync(options.screenshot, screenshot);
  const box = await page.evaluate(() => {
    const r = document.getElementById('view').getBoundingClientRect();
    return { x: r.x, y: r.y, width: r.width, height: r.height };
  });
  const image = decode_png(screenshot);
  const pixels = analyse_pixels(image, box);
  check(pixels.drawn > pixels.total / 100 && pixels.colours > 1,
    `the view is not blank (${pixels.drawn} of ${pixels.total} pixels drawn, ${pixels.colours} colours)`);
  if (options.red === 'yes') check(pixels.red > 0, `red pixels (border edges) seen: ${pixels.red}`);
  if (options.red === 'no') check(pixels.red === 0, `no red pixel (no border edge): ${pixels.red}`);

  await check_markers(page, box, image);

  // A click on the first ambiguous site (or, without one, the first hole) of the list flies the
  // camera there.
  const problem = (await page.$('ol.problems li[data-kind="ambiguous"]')) || (await page.$('ol.problems li'));
  if (problem) {
    const what = await problem.evaluate((li) => (li.dataset.kind === 'ambiguous' ? 'ambiguous site' : li.dataset.kind || 'problem'));
    await problem.click();
    await page.waitForTimeout(1200);
    const moved = decode_png(await page.screenshot({ type: 'png' }));
    const after = analyse_pixels(moved, box);
    const changed = count_changed_pixels(image, moved, box);
    check(changed > pixels.total / 100,
      `a click on the first listed ${what} moves the view (${changed} pixels changed, ${pixels.drawn} -> ${after.drawn} drawn)`);
  }

  if (options.json) {
    const embedded = await page.evaluate(() => document.getElementById('report-json').textContent);
    const expected = JSON.parse(readFileSync(options.json, 'utf8'));
    let same = false;
    try { same = isDeepStrictEqual(JSON.parse(embedded), expected); } catch (error) { same = false; }
    check(same, `report-json equals ${options.json}`);
  }
  check(console_errors.length === 0, `no console error${console_errors.length ? ': ' + console_errors.slice(0, 3).join(' | ') : ''}`);
  check(requests.length === 0, `no network request${requests.length ? ': ' + requests.slice(0, 3).join(' ') : ''}`);
} catch (error) {
  check(false, `the page could not be checked: ${error.message}`);
} finally {
  if (context) await context.close();
  rmSync(profile, { recursive: true, force: true });
}
console.log(`${options.page}: ${failures.length ? 'FAILED' : 'passed'}`);
process.exit(failures.length ? 1 : 0);
