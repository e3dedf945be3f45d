// The run folder as the server gives it under /run/: its tables, and its
// frames fetched, decoded and kept in a byte-bounded cache (least recently
// used dropped first) so that playback reads ahead of the slider.
import { parseCsv, parseFrame, parseShapes } from './view_format.js';

const CACHE_BYTES = 512 * 1024 * 1024;
const MAX_IN_FLIGHT = 4;

export class RunSource {
  constructor(base = '/run/') {
    this.base = base;
    this.index = { rows: 0, columns: {} }; // view/index.csv
    this.indexText = '';
    this.cache = new Map(); // slider position -> {promise, frame, error, bytes}; insertion order is recency
    this.cachedBytes = 0;
    this.inFlight = 0;
  }

  get frameCount() {
    return this.index.rows;
  }

  // Text of a run file; null for a file that is not there (yet).
  async text(path) {
    const response = await fetch(this.base + path, { cache: 'no-store' });
    if (response.status === 404) return null;
    if (!response.ok) throw new Error(`${path}: HTTP ${response.status}`);
    return response.text();
  }

  // The templates and plane ids; null while the run has not written them.
  async loadShapes() {
    const response = await fetch(this.base + 'view/shapes.bin', { cache: 'no-store' });
    if (response.status === 404) return null;
    if (!response.ok) throw new Error(`view/shapes.bin: HTTP ${response.status}`);
    const shapes = parseShapes(await response.arrayBuffer());
    this.shapeCount = shapes.templates.length;
    return shapes;
  }

  // A frame naming templates past those loaded (fragments of grains that
  // broke: the run writes shapes.bin again before such a frame) waits for
  // shapes.bin to be read again, and onShapes(shapes) to take them.
  async withShapes(frame) {
    let most = -1;
    for (let i = 0; i < frame.n; i++) most = Math.max(most, frame.template[i]);
    if (this.shapeCount === undefined || most < this.shapeCount) return frame;
    this.reloading ??= this.loadShapes().finally(() => (this.reloading = null));
    const shapes = await this.reloading;
    if (shapes && this.onShapes) this.onShapes(shapes);
    return frame;
  }

  // Re-reads index.csv; true when it changed. A resumed run may cut it back,
  // so frames past its end are dropped from the cache.
  async refreshIndex() {
    const text = (await this.text('view/index.csv')) ?? '';
    if (text === this.indexText) return false;
    this.indexText = text;
    this.index = parseCsv(text);
    for (const k of [...this.cache.keys()]) if (k >= this.frameCount) this.drop(k);
    return true;
  }

  fileName(k) {
    return `view/frame_${String(this.index.columns.frame[k]).padStart(6, '0')}.bin`;
  }

  // The decoded frame at slider position k (a promise, shared by all callers).
  load(k) {
    const hit = this.cache.get(k);
    if (hit?.error) this.drop(k); // asked again: try again
    else if (hit) {
      this.cache.delete(k); // re-insert: most recently used
      this.cache.set(k, hit);
      return hit.promise;
    }
    const entry = { bytes: 0, frame: null, error: null, promise: null };
    this.inFlight++;
    entry.promise = fetch(this.base + this.fileName(k))
      .then((r) => {
        if (!r.ok) throw new Error(`${this.fileName(k)}: HTTP ${r.status}`);
        return r.arrayBuffer();
      })
      .then((buffer) => {
        entry.bytes = buffer.byteLength;
        this.cachedBytes += entry.bytes;
        this.evict(k);
        return this.withShapes(parseFrame(buffer));
      })
      .then((frame) => {
        entry.frame = frame;
        return frame;
      })
      .catch((error) => {
        entry.error = error; // kept so that playback stops on it rather than refetch every tick
        throw error;
      })
      .finally(() => this.inFlight--);
    this.cache.set(k, entry);
    return entry.promise;
  }

  // The frame at k if it is decoded already, else null (and its fetch
  // started); throws when its fetch failed.
  get(k) {
    const e = this.cache.get(k);
    if (e?.error) throw e.error;
    if (e?.frame) return e.frame;
    if (!e) this.load(k).catch(() => {});
    return null;
  }

  // Starts fetching the next `count` frames after k (wrapping when `wrap`),
  // a few at a time so that the frame wanted now is not queued behind them.
  prefetch(k, count, wrap) {
    for (let i = 1; i <= count && this.inFlight < MAX_IN_FLIGHT; i++) {
      let j = k + i;
      if (j >= this.frameCount) {
        if (!wrap) break;
        j %= this.frameCount;
      }
      if (!this.cache.has(j)) this.load(j).catch(() => {});
    }
  }

  drop(k) {
    const e = this.cache.get(k);
    if (!e) return;
    this.cachedBytes -= e.bytes;
    this.cache.delete(k);
  }

  clear() {
    for (const k of [...this.cache.keys()]) this.drop(k);
  }

  evict(keep) {
    for (const k of this.cache.keys()) {
      if (this.cachedBytes <= CACHE_BYTES) break;
      if (k !== keep && this.cache.get(k).bytes > 0) this.drop(k);
    }
  }
}
