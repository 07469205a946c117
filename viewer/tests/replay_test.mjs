// replay.js without a browser: the verdict of every point (the same rule as
// recall and precision: touching points count neither way), and a committed
// recording read back against its own steps.csv.
//   node replay_test.mjs RUN_DIR
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { judgedPoints, parseReplay, parseSteps } from '../src/replay.js';

const [run] = process.argv.slice(2);
const contact = (body, vertex) => ({ body, vertex, position: [0, 0, 0], depth: 1e-3, direction: [0, 1, 0], force: 0 });
const inside = (body, vertex) => ({ body, vertex, other: 1 - body, depth: 2e-3, position: [0, 0, 0] });

const verdicts = (frame) => Object.fromEntries(judgedPoints(frame).map((p) => [`${p.body}:${p.vertex}`, p.verdict]));
assert.deepEqual(verdicts({ contacts: [contact(0, 1), contact(0, 2), contact(1, 3)], oracle: [inside(0, 1), inside(1, 4)],
  boundary: Int32Array.from([1, 3]) }), { '0:1': 'correct', '0:2': 'false', '1:3': 'touching', '1:4': 'missed' });
assert.deepEqual(verdicts({ contacts: [contact(0, 1)], oracle: null, boundary: null }), { '0:1': null });
const missed = judgedPoints({ contacts: [], oracle: [inside(0, 7)], boundary: null })[0];
assert.equal(missed.trueDepth, 2e-3);
assert.equal(missed.method, false);

// The committed recording: frames every 5 steps, each frame's contacts and
// oracle points as many as steps.csv says.
const manifest = JSON.parse(readFileSync(join(run, 'replay.json'), 'utf8'));
const file = readFileSync(join(run, 'replay.bin'));
const bin = file.buffer.slice(file.byteOffset, file.byteOffset + file.byteLength);
const replay = parseReplay(manifest, bin);
const steps = parseSteps(readFileSync(join(run, 'steps.csv'), 'utf8'));
assert.equal(replay.frames.length, 30);
for (const f of replay.frames) {
  const row = steps.steps.indexOf(f.step);
  assert.equal(f.contacts.length, steps.columns.colliding_points[row], `colliding points at step ${f.step}`);
  assert.equal(f.oracle.length, steps.columns.oracle_points[row], `oracle points at step ${f.step}`);
  assert.equal(f.positions.length, 3 * replay.vertexCount);
  assert.equal(f.aabbs.length % 6, 0);
}
// A manifest pointing past the file is an error, not garbage.
const broken = structuredClone(manifest);
broken.frames[0].positions_offset = bin.byteLength;
assert.throws(() => parseReplay(broken, bin), /outside the file/);
console.log('replay.js checks passed');
