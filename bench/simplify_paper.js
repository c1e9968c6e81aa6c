// SPDX-License-Identifier: MIT
// svgsmooth --simplify T beside Paper.js simplify() (Schneider's curve
// fitting) at equal maximum deviation, on traced and jittered outlines.
// Prints a Markdown table; benchmarks print figures, never assert.
//
// usage: node bench/simplify_paper.js BUILD   (paper from NODE_PATH; see
// scripts/bench-simplify.sh, which installs it under BUILD/paperjs)
//
// For each input and tolerance T:
//  - Conica: `svgsmooth --simplify T` (4 levels) gives the smoothed curve;
//    the subdivision keeps its control points bit for bit, so the kept
//    vertices are the output points equal to an input vertex (12 digits
//    written, the inputs have 4 decimals);
//  - Paper.js: simplify(tol) with the tol that keeps the fewest segments
//    while its result stays within T of every input vertex (Paper's
//    tolerance is its own error measure, so equal maximum deviation is
//    found by measuring);
//  - both measured the same way here: the largest distance of an input
//    vertex from the curve (dense polyline), and the curvature of the curve
//    (circle through three consecutive points of a dense sampling, as
//    `conica combs` draws it): sign changes (wiggles) and total variation.
'use strict';
const fs = require('fs');
const path = require('path');
const { execFileSync } = require('child_process');
const paper = require('paper');

const build = process.argv[2] || 'build';
const svgsmooth = path.join(build, 'bin', 'svgsmooth');
const work = path.join(build, 'bench-simplify');
fs.mkdirSync(work, { recursive: true });
paper.setup(new paper.Size(1000, 1000));

// xorshift64* as in tests/test_simplify.c (BigInt: exact on every platform)
function rng(seed) {
    let s = BigInt.asUintN(64, BigInt(seed));
    return () => {
        s ^= s >> 12n; s ^= BigInt.asUintN(64, s << 25n); s ^= s >> 27n;
        return Number(BigInt.asUintN(64, s * 2685821657736338717n) >> 11n) / 9007199254740992;
    };
}

function jittered(fn, n, amp, seed) {
    const r = rng(seed), pts = [];
    for (let i = 0; i < n; i++) {
        const [x, y] = fn(i / n), a = 2 * Math.PI * r(), d = amp * r();
        pts.push([x + d * Math.cos(a), y + d * Math.sin(a)]);
    }
    return pts;
}

function leafPoints() {
    const t = fs.readFileSync('examples/traced-leaf.svg', 'utf8');
    const d = /id="leaf" d="([^"]*)"/.exec(t)[1];
    return numbers(d);
}

function numbers(s) {
    const v = (s.match(/[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?/g) || []).map(Number), p = [];
    for (let i = 0; i + 1 < v.length; i += 2) p.push([v[i], v[i + 1]]);
    return p;
}

function segDist(p, a, b) {
    const ex = b[0] - a[0], ey = b[1] - a[1], l2 = ex * ex + ey * ey;
    let t = l2 > 0 ? ((p[0] - a[0]) * ex + (p[1] - a[1]) * ey) / l2 : 0;
    t = Math.max(0, Math.min(1, t));
    return Math.hypot(p[0] - a[0] - t * ex, p[1] - a[1] - t * ey);
}

// largest distance of the input vertices from a closed dense polyline
function deviation(pts, poly) {
    let worst = 0;
    for (const p of pts) {
        let d = Infinity;
        for (let i = 0; i < poly.length; i++)
            d = Math.min(d, segDist(p, poly[i], poly[(i + 1) % poly.length]));
        worst = Math.max(worst, d);
    }
    return worst;
}

// curvature at each vertex of a closed polyline: signed 1/R of the circle
// through it and its neighbours; sign changes (ignoring |k| under 1e-3 of
// the largest, flat stretches) and total variation over the smooth parts
// (a jump of more than half the largest |k|, a corner, is not counted)
function curvature(poly) {
    const n = poly.length, k = [];
    for (let i = 0; i < n; i++) {
        const a = poly[(i + n - 1) % n], b = poly[i], c = poly[(i + 1) % n];
        const cr = (b[0] - a[0]) * (c[1] - b[1]) - (b[1] - a[1]) * (c[0] - b[0]);
        const den = Math.hypot(b[0] - a[0], b[1] - a[1]) * Math.hypot(c[0] - b[0], c[1] - b[1]) *
                    Math.hypot(c[0] - a[0], c[1] - a[1]);
        k.push(den > 0 ? 2 * cr / den : 0);
    }
    const sorted = k.map(Math.abs).sort((x, y) => x - y), big = sorted[Math.floor(0.98 * (n - 1))];
    let changes = 0, last = 0, tv = 0;
    for (let i = 0; i < n; i++) {
        if (Math.abs(k[i]) > 1e-3 * big) {
            const s = Math.sign(k[i]);
            if (last && s !== last) changes++;
            last = s;
        }
        const dk = Math.abs(k[(i + 1) % n] - k[i]);
        if (dk < 0.5 * big) tv += dk;
    }
    return { changes, tv };
}

function writeSvg(file, pts) {
    pts.forEach(p => { p[0] = Number(p[0].toFixed(4)); p[1] = Number(p[1].toFixed(4)); });
    const d = 'M' + pts.map(p => p[0].toFixed(4) + ',' + p[1].toFixed(4)).join(' L') + ' Z';
    fs.writeFileSync(file, '<svg xmlns="http://www.w3.org/2000/svg" viewBox="-100 -100 400 400">' +
                     `<path id="p" d="${d}"/></svg>\n`);
}

function conica(file, T, extra) {
    const args = T > 0 ? ['--simplify', String(T), '--lines-as-samples'] : ['--lines-as-samples'];
    const out = execFileSync(svgsmooth, args.concat(extra, ['--precision', '12', file]),
                             { encoding: 'utf8' });
    return numbers(/ d="([^"]*)"/.exec(out)[1]);
}

// Paper.js fits an open path: the polygon from its first vertex round to
// it again (simplify() on the closed path fits worse at its seam: 0.43
// off a radius-10 circle at every tolerance from 1e-3 up, in 0.12.20)
function paperFit(pts, tol) {
    const p = new paper.Path({ segments: pts.concat([pts[0]]), closed: false, insert: false });
    p.simplify(tol);
    const dense = [];
    for (const c of p.curves)
        for (let i = 0; i < 32; i++) {
            const q = c.getPointAtTime(i / 32);
            dense.push([q.x, q.y]);
        }
    return { segments: p.segments.length - 1, dense }; // the last segment is the first again
}

// the Paper.js tolerance (of 160 from 1e-5 to 100, log-spaced) whose result
// stays within T with the fewest segments (its error is not monotonic in the
// tolerance, so a scan, not a bisection)
function paperAt(pts, T) {
    let best = null;
    for (let it = 0; it < 160; it++) {
        const tol = 1e-5 * Math.pow(1e7, it / 159), f = paperFit(pts, tol);
        const dev = deviation(pts, f.dense);
        if (dev <= T && (!best || f.segments < best.segments))
            best = Object.assign(f, { dev, tol });
    }
    return best;
}

const cases = [
    { name: 'traced leaf (examples/traced-leaf.svg, 80 vertices, jitter 0.35)', pts: leafPoints(), T: [0.5, 1] },
    { name: 'circle r 10, 240 samples, jitter 0.02', T: [0.05],
      pts: jittered(t => [10 * Math.cos(2 * Math.PI * t), 10 * Math.sin(2 * Math.PI * t)], 240, 0.02, 1) },
    { name: 'ellipse 20 x 8, 240 samples, jitter 0.02', T: [0.05],
      pts: jittered(t => [20 * Math.cos(2 * Math.PI * t), 8 * Math.sin(2 * Math.PI * t)], 240, 0.02, 2) },
];

console.log('| input | T | method | vertices kept | max deviation | curvature sign changes | curvature TV |');
console.log('|---|---|---|---|---|---|---|');
for (const c of cases) {
    const file = path.join(work, c.name.split(' ')[0] + '.svg');
    writeSvg(file, c.pts);
    const all = conica(file, 0, []), ka = curvature(all);
    console.log(`| ${c.name} | - | every vertex interpolated (--lines-as-samples) | ${c.pts.length} | ` +
                `${deviation(c.pts, all).toFixed(3)} | ${ka.changes} | ${ka.tv.toFixed(3)} |`);
    for (const T of c.T) {
        const sm = conica(file, T, []), input = new Set(c.pts.map(p => p.join(' ')));
        const kept = sm.filter(p => input.has(p.join(' '))).length;
        const kc = curvature(sm);
        console.log(`| | ${T} | svgsmooth --simplify ${T} | ${kept} | ${deviation(c.pts, sm).toFixed(3)} | ` +
                    `${kc.changes} | ${kc.tv.toFixed(3)} |`);
        const pf = paperAt(c.pts, T);
        if (!pf) {
            console.log(`| | ${T} | Paper.js simplify() | no tolerance within ${T} | | | |`);
            continue;
        }
        const kp = curvature(pf.dense);
        console.log(`| | ${T} | Paper.js simplify(${pf.tol.toPrecision(3)}) | ${pf.segments} | ` +
                    `${pf.dev.toFixed(3)} | ${kp.changes} | ${kp.tv.toFixed(3)} |`);
    }
}
