// Readers of a run's view/ files (docs/view-format.md) and its CSV tables.
// Frames are decoded as typed-array views into the fetched buffer: no copy,
// so a 100,000-body frame decodes in microseconds.

const PLANE_BIT = 0x80000000;
export { PLANE_BIT };

function checkMagic(buffer, magic, what, header) {
  if (buffer.byteLength < header) throw new Error(`${what}: ${buffer.byteLength} bytes, shorter than its header`);
  const bytes = new Uint8Array(buffer, 0, Math.min(8, buffer.byteLength));
  const text = String.fromCharCode(...bytes);
  if (text !== magic) throw new Error(`${what}: not a ${magic} file`);
  const version = new DataView(buffer).getUint32(8, true);
  if (version < 2 || version > 4) throw new Error(`${what}: version ${version} unknown (this viewer reads 2 to 4)`);
  return version;
}

// shapes.bin: each template's triangle mesh (body frame) and the plane walls' ids.
export function parseShapes(buffer) {
  checkMagic(buffer, 'GJKSHAPE', 'shapes.bin', 24);
  const dv = new DataView(buffer);
  const T = dv.getUint32(12, true), P = dv.getUint32(16, true);
  const templates = [];
  let o = 24;
  for (let t = 0; t < T; t++) {
    const V = dv.getUint32(o, true), F = dv.getUint32(o + 4, true);
    o += 8;
    if (o + 12 * V + 12 * F > buffer.byteLength) throw new Error(`shapes.bin: template ${t} runs past the end`);
    const vertices = new Float32Array(buffer, o, 3 * V);
    o += 12 * V;
    const triangles = new Uint32Array(buffer, o, 3 * F);
    o += 12 * F;
    for (let i = 0; i < triangles.length; i++)
      if (triangles[i] >= V) throw new Error(`shapes.bin: template ${t} has a triangle naming vertex ${triangles[i]} of ${V}`);
    templates.push({ vertices, triangles });
  }
  if (o + 4 * P > buffer.byteLength) throw new Error('shapes.bin: plane ids run past the end');
  return { templates, planeIds: new Uint32Array(buffer, o, P) };
}

// frame_NNNNNN.bin: bodies, touching contacts and plane walls at one output.
export function parseFrame(buffer) {
  const version = checkMagic(buffer, 'GJKFRAME', 'frame', 40);
  const dv = new DataView(buffer);
  const n = dv.getUint32(12, true), m = dv.getUint32(16, true), p = dv.getUint32(20, true);
  const align4 = (x) => Math.ceil(x / 4) * 4; // arithmetic, not bit operations: sizes may pass 2^31
  // Version 3 adds the bonds of bonded assemblies: a count, then 21 bytes each.
  const before = align4(40 + 61 * n) + 44 * m + 24 * p + 40;
  const k = version >= 3 && buffer.byteLength >= before + 4 ? dv.getUint32(before, true) : 0;
  const bondsEnd = before + (version >= 3 ? 4 + 21 * k : 0);
  if (version < 4 ? buffer.byteLength !== bondsEnd : buffer.byteLength < align4(bondsEnd) + 4)
    throw new Error(`frame: ${buffer.byteLength} bytes, its header says ${version < 4 ? bondsEnd : 'at least ' + (align4(bondsEnd) + 4)}`);
  let o = 40;
  const take = (Type, count) => {
    const a = new Type(buffer, o, count);
    o += count * Type.BYTES_PER_ELEMENT;
    return a;
  };
  const pad = () => { // to a multiple of 4 over zero bytes, as the writer pads
    const end = align4(o);
    if (end > buffer.byteLength) throw new Error('frame: cut short in its padding');
    for (let i = o; i < end; i++) if (dv.getUint8(i) !== 0) throw new Error('frame: padding that is not zero');
    o = end;
  };
  const f = {
    n, m, p,
    time: dv.getFloat64(24, true),
    steps: Number(dv.getBigUint64(32, true)),
    byteLength: buffer.byteLength,
    position: take(Float32Array, 3 * n),
    quaternion: take(Float32Array, 4 * n), // w, x, y, z
    velocity: take(Float32Array, 3 * n),
    angularVelocity: take(Float32Array, 3 * n),
    template: take(Uint32Array, n),
    id: take(Uint32Array, n),
    flags: take(Uint8Array, n),
  };
  pad();
  f.contactFirst = take(Uint32Array, m); // body index, or PLANE_BIT + plane
  f.contactSecond = take(Uint32Array, m);
  f.contactPoint = take(Float32Array, 3 * m);
  f.contactNormal = take(Float32Array, 3 * m);
  f.contactForce = take(Float32Array, 3 * m); // on the second body
  f.planePoint = take(Float32Array, 3 * p);
  f.planeNormal = take(Float32Array, 3 * p);
  f.cellAxes = take(Uint32Array, 1)[0]; // bit 0 x, 1 y, 2 z; 0: not periodic
  f.cell = take(Float32Array, 9); // lo, hi, tilts xy, xz, yz
  f.bonds = k;
  if (version >= 3) o += 4;
  f.bondFirst = take(Uint32Array, k); // body indices
  f.bondSecond = take(Uint32Array, k);
  f.bondPoint = take(Float32Array, 3 * k); // the glued face's centre
  f.bondIntact = take(Uint8Array, k); // 1 holds, 0 broken
  // Version 4 ends with the channel block: per-body channels by name
  // (docs/view-format.md), each {unit, components, values: Float32Array}.
  f.channels = Object.create(null); // no prototype: a channel may have any name
  if (version >= 4) {
    pad();
    const count = take(Uint32Array, 1)[0];
    for (let c = 0; c < count; c++) {
      if (o + 12 > buffer.byteLength) throw new Error(`frame: channel ${c} runs past the end`);
      const components = dv.getUint32(o, true), nameBytes = dv.getUint32(o + 4, true), unitBytes = dv.getUint32(o + 8, true);
      o += 12;
      if (components < 1 || components > 4 || nameBytes < 1 || nameBytes > 64 || unitBytes > 64 || o + nameBytes + unitBytes > buffer.byteLength)
        throw new Error(`frame: channel ${c} has a size, a name or a unit length it cannot have`);
      const name = String.fromCharCode(...new Uint8Array(buffer, o, nameBytes));
      const unit = String.fromCharCode(...new Uint8Array(buffer, o + nameBytes, unitBytes));
      if (!/^[a-z0-9_]+$/.test(name) || Object.hasOwn(f.channels, name)) throw new Error(`frame: channel ${c} has a bad or repeated name`);
      if (!/^[\x20-\x7e]*$/.test(unit)) throw new Error(`frame: channel ${name} has a unit that is not printable ASCII`);
      o += nameBytes + unitBytes;
      pad();
      if (o + 4 * components * n > buffer.byteLength) throw new Error(`frame: channel ${name} runs past the end`);
      f.channels[name] = { unit, components, values: take(Float32Array, components * n) };
    }
  }
  if (o !== buffer.byteLength) throw new Error(`frame: ${buffer.byteLength} bytes, its contents end at ${o}`);
  for (let b = 0; b < k; b++)
    if (f.bondFirst[b] >= n || f.bondSecond[b] >= n) throw new Error(`frame: bond ${b} names a body it does not have`);
  for (let c = 0; c < m; c++) {
    const first = f.contactFirst[c];
    if (f.contactSecond[c] >= n || (first >= PLANE_BIT ? first - PLANE_BIT >= p : first >= n))
      throw new Error(`frame: contact ${c} names a body or plane it does not have`);
  }
  return f;
}

// A numeric CSV with a header row: {columns: {name: Float64Array}, rows}.
// A last line without its newline is still being written by the run: skipped.
export function parseCsv(text) {
  const lines = text.split('\n');
  lines.pop(); // the part after the last newline
  while (lines.length > 0 && lines[lines.length - 1].trim() === '') lines.pop();
  if (lines.length === 0) return { columns: {}, rows: 0 };
  const names = lines[0].split(',').map((s) => s.trim());
  const rows = lines.length - 1;
  const columns = Object.fromEntries(names.map((name) => [name, new Float64Array(rows)]));
  for (let r = 0; r < rows; r++) {
    const cells = lines[r + 1].split(',');
    for (let c = 0; c < names.length; c++) columns[names[c]][r] = Number(cells[c]);
  }
  return { columns, rows };
}
