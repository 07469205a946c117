// Reads a run's replay (replay.json + replay.bin, written by
// experiments/results/replay_file.cpp) into plain frames for the views.
// Every buffer is little-endian and 4-byte aligned, so typed-array views
// read it in place; a manifest that points outside the file is an error.

export const FORCE_NAMES = { 0: 'computed', 1: 'held', 2: 'extrapolated', 3: 'tracked', 255: 'none' };

function view(bin, Type, offset, count, per) {
  const bytes = count * per * Type.BYTES_PER_ELEMENT;
  if (offset < 0 || offset + bytes > bin.byteLength || offset % 4 !== 0)
    throw new Error(`replay.bin: a buffer at byte ${offset} (${bytes} bytes) is outside the file`);
  return new Type(bin, offset, count * per);
}

export function parseReplay(manifest, bin) {
  if (manifest.schema !== 'tcbench.replay/1') throw new Error(`replay.json: unknown schema ${manifest.schema}`);
  const triangles = view(bin, Uint32Array, manifest.triangles.offset, manifest.triangles.count, 3);
  const surfaceMap = view(bin, Uint32Array, manifest.surface_map.offset, manifest.surface_map.count, 2);
  const vertexCount = manifest.surface_map.count;
  for (const i of triangles) if (i >= vertexCount) throw new Error('replay.bin: a triangle names a vertex past the surface');
  const contactBytes = manifest.layouts.contact.bytes;
  const oracleBytes = manifest.layouts.oracle_point.bytes;
  const frames = manifest.frames.map((f) => ({
    step: f.step,
    time_s: f.time_s,
    positions: view(bin, Float32Array, f.positions_offset, vertexCount, 3),
    contacts: readContacts(bin, f.contacts, contactBytes),
    oracle: f.oracle ? readOracle(bin, f.oracle, oracleBytes) : null,
    // Touching points (recorded since the boundary buffer was added; older replays have none).
    boundary: f.boundary ? view(bin, Int32Array, f.boundary.offset, f.boundary.count, 2) : null,
    aabbs: f.aabbs ? view(bin, Float32Array, f.aabbs.offset, f.aabbs.count, 6) : null,
    cells: f.cells ? view(bin, Int32Array, f.cells.offset, f.cells.count, 3) : null,
    cellsTruncated: f.cells ? !!f.cells.truncated : false,
  }));
  return {
    bodies: manifest.bodies.map((b) => ({ name: b.name, firstVertex: b.surface_vertices[0], vertexCount: b.surface_vertices[1] })),
    triangles,
    surfaceMap,
    vertexCount,
    every: manifest.every,
    cellSize: manifest.debug ? manifest.debug.cell_size_m : null,
    frames,
  };
}

// Fixed-size records at where.offset, each read by read(data, at).
function readRecords(bin, where, bytes, what, read) {
  if (where.offset + where.count * bytes > bin.byteLength) throw new Error(`replay.bin: ${what} outside the file`);
  const data = new DataView(bin, where.offset, where.count * bytes);
  const out = [];
  for (let i = 0; i < where.count; ++i) out.push(read(data, i * bytes));
  return out;
}

const float3 = (data, at) => [0, 4, 8].map((k) => data.getFloat32(at + k, true));

function readContacts(bin, where, bytes) {
  return readRecords(bin, where, bytes, 'contacts', (data, at) => ({
    body: data.getInt32(at, true), vertex: data.getInt32(at + 4, true), other: data.getInt32(at + 8, true),
    tet: data.getInt32(at + 12, true), depth: data.getFloat32(at + 16, true), direction: float3(data, at + 20),
    position: float3(data, at + 32), force: data.getUint8(at + 44), depthSource: data.getUint8(at + 45),
  }));
}

function readOracle(bin, where, bytes) {
  return readRecords(bin, where, bytes, 'oracle points', (data, at) => ({
    body: data.getInt32(at, true), vertex: data.getInt32(at + 4, true), other: data.getInt32(at + 8, true),
    depth: data.getFloat32(at + 12, true), position: float3(data, at + 16),
  }));
}

// Every point of a frame with what the method and the oracle said of it:
// verdict 'correct' (both), 'missed' (oracle only), 'false' (method only),
// 'touching' (method only, exactly on another body's surface by the oracle:
// recall and precision count it neither way), or null when the oracle did
// not run on this frame.
export function judgedPoints(frame) {
  const key = (p) => `${p.body}:${p.vertex}`;
  const points = new Map();
  for (const c of frame.contacts) points.set(key(c), { ...c, method: true, truth: false, trueDepth: NaN });
  if (frame.oracle) {
    for (const o of frame.oracle) {
      const p = points.get(key(o));
      if (p) { p.truth = true; p.trueDepth = o.depth; }
      else points.set(key(o), { ...o, method: false, truth: true, trueDepth: o.depth, force: 255, direction: null, depth: NaN });
    }
  }
  const out = [...points.values()];
  const touching = new Set();
  if (frame.boundary) for (let i = 0; i < frame.boundary.length; i += 2) touching.add(`${frame.boundary[i]}:${frame.boundary[i + 1]}`);
  for (const p of out) {
    p.verdict = !frame.oracle ? null : p.method && p.truth ? 'correct' : p.truth ? 'missed'
      : touching.has(key(p)) ? 'touching' : 'false';
  }
  return out;
}

// steps.csv into columns of numbers (empty cells: NaN), indexed by step.
export function parseSteps(text) {
  const lines = text.split('\n').filter((l) => l.length > 0);
  if (lines.length === 0) return { columns: {}, steps: [] };
  const names = lines[0].split(',');
  const columns = Object.fromEntries(names.map((n) => [n, new Float64Array(lines.length - 1)]));
  for (let r = 1; r < lines.length; ++r) {
    const cells = lines[r].split(',');
    names.forEach((n, c) => { columns[n][r - 1] = cells[c] === '' || cells[c] === undefined ? NaN : Number(cells[c]); });
  }
  return { columns, steps: columns.step ? Array.from(columns.step) : [] };
}

export async function loadRun(base) {
  const get = async (file, how) => {
    const response = await fetch(`${base}/${file}`);
    if (!response.ok) return null;
    return how === 'json' ? response.json() : how === 'bin' ? response.arrayBuffer() : response.text();
  };
  const [manifest, bin, steps, runJson] = await Promise.all([get('replay.json', 'json'), get('replay.bin', 'bin'),
    get('steps.csv', 'text'), get('run.json', 'json')]);
  if (!manifest || !bin) throw new Error(`${base}: no replay (record it with tcbench run ... --record N)`);
  const replay = parseReplay(manifest, bin);
  replay.steps = steps ? parseSteps(steps) : null;
  replay.run = runJson;
  return replay;
}
