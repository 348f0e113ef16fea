// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Writes the OFF file IN with every coordinate multiplied by 2^K, for the browser test of soups
// at extreme scales. A power of two changes only the exponents, so the scaled soup is the same
// soup in other units; a coordinate that would not scale back exactly is refused.
//   node scale_off.mjs IN.off OUT.off K
import { readFileSync, writeFileSync } from 'node:fs';

const [input, output, k_text] = process.argv.slice(2);
if (!input || !output || k_text === undefined) {
  console.error('usage: node scale_off.mjs IN.off OUT.off K');
  process.exit(2);
}
const k = Number(k_text);
// 2^k as a product of two factors, each a normal double, for |k| up to 2044.
const half = Math.trunc(k / 2);
const scale = (x) => (x * 2 ** half) * 2 ** (k - half);
const unscale = (x) => (x * 2 ** -half) * 2 ** -(k - half);

const lines = readFileSync(input, 'utf8').split('\n').map((l) => l.split('#')[0].trim()).filter((l) => l !== '');
let first = lines[0].replace(/^OFF/, '').trim();
let next = 1;
if (first === '') first = lines[next++];
const [vertices, faces] = first.split(/\s+/).map(Number);
const out = ['OFF', `${vertices} ${faces} 0`];
for (let v = 0; v < vertices; ++v) {
  const xyz = lines[next + v].split(/\s+/).slice(0, 3).map(Number);
  const scaled = xyz.map(scale);
  if (scaled.some((s, i) => unscale(s) !== xyz[i])) {
    console.error(`scale_off: vertex ${v} does not scale exactly by 2^${k}`);
    process.exit(1);
  }
  out.push(scaled.map(String).join(' '));
}
for (let f = 0; f < faces; ++f) out.push(lines[next + vertices + f]);
writeFileSync(output, out.join('\n') + '\n');
