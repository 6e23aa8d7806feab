#!/usr/bin/env node
// Independent expression oracles (issue 14): classify rendered faces with a facial-expression network
// nobody here wrote and print the confusion table. Two networks, chosen with --network:
//   human   @vladmandic/human's emotion model (oarriaga's mini-Xception on FER-2013: 64×64 grey crops of
//           its face-mesh box); the oracle.
//   faceapi @vladmandic/face-api's FaceExpressionNet (112×112 colour crops of an SSD MobileNet v1 face
//           box; trained by face-api.js on a different image set): a second opinion, so that a change
//           is not tuned to one network's quirks.
// Offline by construction: the pure-JS CPU backend of TensorFlow.js and the models shipped inside the
// npm packages (models/*.json + *.bin, model/*manifest.json + *.bin); any other fetch fails. The
// "node-wasm" builds are used because they take tfjs from node_modules (the "node" builds need
// @tensorflow/tfjs-node, whose native library is downloaded at install time); wasm is not used.
//
// Usage: node classify.cjs [--network human|faceapi] [--min N] [--json FILE] EXPECTED=IMAGE.png ...
//   EXPECTED is one of neutral, happiness, sadness, anger, fear, disgust, surprise.
//   Prints a Markdown table (rows = intended expression, columns = the network's scores) and
//   "correct: k of n"; exit status 1 when fewer than N (default: all) are top-1 correct, 2 on bad input.
//   Several images of one EXPECTED (e.g. the same face at several camera distances) make one row
//   with their mean scores.
'use strict';
const fs = require('node:fs');
const path = require('node:path');
const zlib = require('node:zlib');

// The network's labels (human src/face/emotion.ts) and emoface's names for them.
const LABELS = ['neutral', 'happy', 'sad', 'angry', 'fear', 'disgust', 'surprise'];
const OURS = ['neutral', 'happiness', 'sadness', 'anger', 'fear', 'disgust', 'surprise'];

// Minimal PNG decoder (8-bit RGB/RGBA, not interlaced: what core::encode_png writes), PNG spec §9
// filters; returns RGB bytes.
function decodePng(file) {
  const buf = fs.readFileSync(file);
  const sig = Buffer.from([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]);
  if (buf.length < 8 || !buf.subarray(0, 8).equals(sig)) throw new Error(`${file}: not a PNG`);
  let pos = 8, width = 0, height = 0, channels = 0; const idat = [];
  while (pos + 8 <= buf.length) {
    const len = buf.readUInt32BE(pos); const type = buf.toString('latin1', pos + 4, pos + 8);
    if (pos + 12 + len > buf.length) throw new Error(`${file}: truncated ${type} chunk`);
    const data = buf.subarray(pos + 8, pos + 8 + len);
    if (type === 'IHDR') {
      width = data.readUInt32BE(0); height = data.readUInt32BE(4);
      const depth = data[8], colour = data[9], interlace = data[12];
      if (depth !== 8 || interlace !== 0 || (colour !== 2 && colour !== 6))
        throw new Error(`${file}: only 8-bit RGB/RGBA non-interlaced PNGs (depth ${depth}, colour type ${colour})`);
      channels = colour === 2 ? 3 : 4;
    } else if (type === 'IDAT') idat.push(data);
    else if (type === 'IEND') break;
    pos += 12 + len;
  }
  if (!width || !height || !idat.length) throw new Error(`${file}: missing IHDR or IDAT`);
  const raw = zlib.inflateSync(Buffer.concat(idat));
  const stride = width * channels;
  if (raw.length !== height * (stride + 1)) throw new Error(`${file}: image data has the wrong size`);
  const out = new Uint8Array(width * height * 3); const prev = new Uint8Array(stride); const cur = new Uint8Array(stride);
  for (let y = 0; y < height; ++y) {
    const f = raw[y * (stride + 1)]; const row = raw.subarray(y * (stride + 1) + 1, (y + 1) * (stride + 1));
    for (let i = 0; i < stride; ++i) {
      const a = i >= channels ? cur[i - channels] : 0, b = prev[i], c = i >= channels ? prev[i - channels] : 0;
      let p;
      switch (f) {
        case 0: p = 0; break; case 1: p = a; break; case 2: p = b; break; case 3: p = (a + b) >> 1; break;
        case 4: { const q = a + b - c, pa = Math.abs(q - a), pb = Math.abs(q - b), pc = Math.abs(q - c);
          p = pa <= pb && pa <= pc ? a : pb <= pc ? b : c; break; }
        default: throw new Error(`${file}: bad filter ${f} on row ${y}`);
      }
      cur[i] = (row[i] + p) & 255;
    }
    for (let x = 0; x < width; ++x) for (let k = 0; k < 3; ++k) out[(y * width + x) * 3 + k] = cur[x * channels + k];
    prev.set(cur);
  }
  return { width, height, data: out };
}

function usage(msg) {
  console.error(`classify.cjs: ${msg}`);
  console.error('usage: node classify.cjs [--network human|faceapi] [--min N] [--json FILE] EXPECTED=IMAGE.png ...');
  process.exit(2);
}

function parseArgs(argv) {
  const opts = { min: -1, json: '', network: 'human', items: [] };
  for (let i = 0; i < argv.length; ++i) {
    const a = argv[i];
    if (a === '--min' || a === '--json' || a === '--network') {
      if (i + 1 >= argv.length) usage(`${a} needs a value`);
      const v = argv[++i];
      if (a === '--min') {
        if (!/^[0-9]+$/.test(v)) usage(`--min: not a count: ${v}`);
        opts.min = Number(v);
      } else if (a === '--network') {
        if (!['human', 'faceapi'].includes(v)) usage(`--network: human or faceapi, not ${v}`);
        opts.network = v;
      } else opts.json = v;
      continue;
    }
    const eq = a.indexOf('=');
    if (eq <= 0) usage(`expected EXPECTED=IMAGE.png, got ${a}`);
    const expected = a.slice(0, eq);
    if (!OURS.includes(expected)) usage(`unknown expression ${expected} (one of ${OURS.join(', ')})`);
    opts.items.push({ expected, file: a.slice(eq + 1) });
  }
  if (opts.items.length === 0) usage('no images');
  if (opts.min < 0) opts.min = new Set(opts.items.map((it) => it.expected)).size;
  return opts;
}

async function makeHuman() {
  require('@tensorflow/tfjs-core');
  require('@tensorflow/tfjs-backend-cpu');
  // The package's export map lists its subpaths without "./", so resolve the package root by hand.
  const root = path.dirname(path.dirname(require.resolve('@vladmandic/human')));
  const H = require(path.join(root, 'dist', 'human.node-wasm.js'));
  const modelDir = path.join(root, 'models');
  const prefix = 'http://models.local/';
  globalThis.fetch = async (url) => {
    const u = String(url);
    if (!u.startsWith(prefix)) throw new Error(`offline oracle: refusing to fetch ${u}`);
    return new Response(fs.readFileSync(path.join(modelDir, u.slice(prefix.length))), { status: 200 });
  };
  const human = new H.Human({
    backend: 'cpu', modelBasePath: prefix, debug: false, cacheModels: false,
    // Every image is a new face: no frame-to-frame caching or skipping (human's video defaults).
    cacheSensitivity: 0, skipAllowed: false, filter: { enabled: false },
    body: { enabled: false }, hand: { enabled: false }, object: { enabled: false },
    gesture: { enabled: false }, segmentation: { enabled: false },
    face: {
      enabled: true, detector: { rotation: false, maxDetected: 1, skipFrames: 0 },
      mesh: { enabled: true }, iris: { enabled: false }, description: { enabled: false },
      emotion: { enabled: true, minConfidence: 0, skipFrames: 0 }, antispoof: { enabled: false },
      liveness: { enabled: false },
    },
  });
  await human.load();
  if (!human.models.models.emotion) throw new Error('the emotion model did not load');
  return human;
}

// face-api's labels, in our names
const FACEAPI = { neutral: 'neutral', happy: 'happiness', sad: 'sadness', angry: 'anger', fearful: 'fear',
  disgusted: 'disgust', surprised: 'surprise' };

// A classifier: image → { faces, scores (our names) }.
async function makeClassifier(network) {
  if (network === 'human') {
    const human = await makeHuman();
    return async (img) => {
      const t = human.tf.tensor4d(Float32Array.from(img.data), [1, img.height, img.width, 3], 'float32');
      const r = await human.detect(t);
      t.dispose();
      const scores = Object.fromEntries(OURS.map((n) => [n, 0]));
      if (r.face.length > 0) {
        for (const e of r.face[0].emotion) scores[OURS[LABELS.indexOf(e.emotion)]] = e.score;
      }
      return { faces: r.face.length, scores };
    };
  }
  const tf = require('@tensorflow/tfjs');
  const faceapi = require('@vladmandic/face-api/dist/face-api.node-wasm.js');
  await tf.setBackend('cpu');
  await tf.ready();
  const dir = path.join(path.dirname(require.resolve('@vladmandic/face-api/package.json')), 'model');
  await faceapi.nets.ssdMobilenetv1.loadFromDisk(dir);
  await faceapi.nets.faceExpressionNet.loadFromDisk(dir);
  return async (img) => {
    const t = tf.tensor3d(Int32Array.from(img.data), [img.height, img.width, 3], 'int32');
    const r = await faceapi.detectSingleFace(t, new faceapi.SsdMobilenetv1Options({ minConfidence: 0.2 }))
      .withFaceExpressions();
    t.dispose();
    const scores = Object.fromEntries(OURS.map((n) => [n, 0]));
    if (r) for (const [k, v] of Object.entries(r.expressions)) scores[FACEAPI[k]] = Math.trunc(100 * v) / 100;
    return { faces: r ? 1 : 0, scores };
  };
}

async function main() {
  const opts = parseArgs(process.argv.slice(2));
  const pngs = opts.items.map((it) => {
    try { return decodePng(it.file); } catch (e) { usage(e.message); }
    return null;
  });
  const classify = await makeClassifier(opts.network);
  // One row per intended expression, in the order of first appearance: several images of the same
  // expression (e.g. the same face at several camera distances) are one row whose scores are the
  // mean of theirs, so that the verdict does not hang on one render's pixels.
  const images = [];
  const rows = [];
  for (let i = 0; i < opts.items.length; ++i) {
    const { faces, scores } = await classify(pngs[i]);
    images.push({ expected: opts.items[i].expected, file: opts.items[i].file, faces, scores });
    let row = rows.find((r) => r.expected === opts.items[i].expected);
    if (!row) rows.push(row = { expected: opts.items[i].expected, images: 0, faces: 0, scores: {} });
    row.images += 1;
    row.faces += faces > 0 ? 1 : 0;
    for (const n of OURS) row.scores[n] = (row.scores[n] || 0) + scores[n];
  }
  for (const r of rows) {
    // an image without a face counts as scoring 0 everywhere; no face in any image: 'no face'
    for (const n of OURS) r.scores[n] = Math.round(100 * r.scores[n] / r.images) / 100;
    r.top = r.faces > 0 ? OURS[0] : 'no face';
    for (const n of OURS) if (r.faces > 0 && r.scores[n] > r.scores[r.top]) r.top = n;
    r.correct = r.top === r.expected;
  }
  const correct = rows.filter((r) => r.correct).length;
  const several = rows.some((r) => r.images > 1);
  console.log(`| intended | ${OURS.join(' | ')} | top-1 |`);
  console.log(`|---|${OURS.map(() => '---').join('|')}|---|`);
  for (const r of rows) {
    const cells = OURS.map((n) => (n === r.top ? `**${r.scores[n].toFixed(2)}**` : r.scores[n].toFixed(2)));
    console.log(`| ${r.expected} | ${cells.join(' | ')} | ${r.top}${r.correct ? ' ✓' : ''} |`);
  }
  if (several) console.log(`(scores: the mean over each expression's ${images.length / rows.length} images)`);
  console.log(`correct: ${correct} of ${rows.length} (required: ${opts.min})`);
  if (opts.json) {
    fs.writeFileSync(opts.json, JSON.stringify({ network: opts.network, correct, required: opts.min, rows, images },
      null, 1) + '\n');
  }
  process.exit(correct >= opts.min ? 0 : 1);
}

main().catch((e) => { console.error(`classify.cjs: ${e.stack || e}`); process.exit(2); });
