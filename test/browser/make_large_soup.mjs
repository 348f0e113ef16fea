// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Writes a torus of 2 * m * n triangles as an OFF file, with a hole of h x h quads cut out
// (h = 0: closed), for the browser test of a large report.
//   node make_large_soup.mjs OUT.off [m] [n] [h]      (defaults: 1000 500 4 -> 999,968 triangles)
import { createWriteStream } from 'node:fs';

const [out, m_text = '1000', n_text = '500', h_text = '4'] = process.argv.slice(2);
if (!out) { console.error('usage: node make_large_soup.mjs OUT.off [m] [n] [h]'); process.exit(2); }
const m = Number(m_text), n = Number(n_text), h = Number(h_text);
const lines = [];
const stream = createWriteStream(out);
const flush = () => { stream.write(lines.join('\n') + '\n'); lines.length = 0; };
const in_hole = (i, j) => i < h && j < h;
let faces = 0;
for (let i = 0; i < m; ++i) for (let j = 0; j < n; ++j) if (!in_hole(i, j)) faces += 2;
lines.push('OFF', `${m * n} ${faces} 0`);
for (let i = 0; i < m; ++i) {
  const u = (2 * Math.PI * i) / m;
  for (let j = 0; j < n; ++j) {
    const v = (2 * Math.PI * j) / n;
    const r = 10 + 3 * Math.cos(v);
    lines.push(`${(r * Math.cos(u)).toFixed(6)} ${(r * Math.sin(u)).toFixed(6)} ${(3 * Math.sin(v)).toFixed(6)}`);
  }
  if (lines.length > 10000) flush();
}
const index = (i, j) => (i % m) * n + (j % n);
for (let i = 0; i < m; ++i) {
  for (let j = 0; j < n; ++j) {
    if (in_hole(i, j)) continue;
    const a = index(i, j), b = index(i + 1, j), c = index(i + 1, j + 1), d = index(i, j + 1);
    lines.push(`3 ${a} ${b} ${c}`, `3 ${a} ${c} ${d}`);
  }
  if (lines.length > 10000) flush();
}
flush();
stream.end();
