// Decoding an .srm file while it arrives: a refined mesh each time enough
// new bytes have come in to change it.
//
//   const progressive = new ProgressiveDecoder(decoder, { onRefine: (mesh, at) => draw(mesh) });
//   for await (const chunk of stream) progressive.push(chunk);
//   progressive.end();
//
// or, with a fetch body: await decodeStream(decoder, response.body, { onRefine }).
//
// The file's header says where each level's refinement flags end and where
// each bit plane of the coefficients ends (decoder.inspect). Those are the
// points where the mesh gains a level or a plane of detail: the decoder runs
// once each time the bytes cross one or more of them, on all the bytes so
// far, so no prefix is decoded twice; and once more for each level passed
// on the way, so that the levels show coarse to fine. `everyBytes` adds
// decodes between them (inside a long plane); the end of the stream adds one
// for the last bytes.

const HEADER_START = 10;  // magic, version, reserved byte, u32 header size (format/srm/README.md)
// The header's declared file size sizes the buffer in one go, but a hostile
// header may declare terabytes: above this size, the buffer doubles as bytes come.
const DECLARED_BYTES_TRUSTED = 64 * 1024 * 1024;

export class ProgressiveDecoder {
  #decoder;
  #options;
  #bytes = new Uint8Array(1024);
  #length = 0;
  #info = null;
  #marks = [];       // the prefix lengths to decode at, rising
  #nextMark = 0;     // index of the first mark not yet crossed
  #decodedAt = 0;    // the length last decoded (successfully or not)
  #levelShown = -1;  // the finest level decoded so far
  #last = null;      // the last mesh decoded
  #error = null;     // the last decode's error, when it failed

  // options: level (-1: the finest), maxVertices, cornerNormals (as
  // decoder.decode's), everyBytes (also decode after this many new bytes; 0:
  // only where a level or plane ends), and onRefine(mesh, { bytesReceived,
  // info, milliseconds }).
  constructor(decoder, options = {}) {
    this.#decoder = decoder;
    this.#options = { level: -1, everyBytes: 0, ...options };
  }

  get bytesReceived() { return this.#length; }
  // The bytes so far (a view: valid until the next push).
  get bytes() { return this.#bytes.subarray(0, this.#length); }
  // The file's header (decoder.inspect's result), once its bytes are in.
  get info() { return this.#info; }
  // The last mesh decoded, and the error of the last decode that failed.
  get mesh() { return this.#last; }
  get error() { return this.#error; }

  // Appends a chunk; decodes when it crosses a level or plane boundary.
  // Returns the refined mesh, or null when the mesh did not change.
  push(chunk) {
    this.#append(chunk);
    if (this.#info === null && !this.#readHeader()) return null;
    const length = this.#length;
    let crossed = false;
    while (this.#nextMark < this.#marks.length && this.#marks[this.#nextMark] <= length) {
      ++this.#nextMark;
      crossed = true;
    }
    const every = this.#options.everyBytes;
    const enough = every > 0 && this.#nextMark > 0 && length - this.#decodedAt >= every;
    if (!crossed && !enough) return null;
    this.#decodeLevelsPassed();
    return this.#decode();
  }

  // Each level the bytes completed since the last decode, below the finest
  // they reach, gets a refinement of its own: coarse to fine, even when one
  // chunk brings the flags of several levels (they are a few bytes each).
  #decodeLevelsPassed() {
    const reached = this.#levelAt(this.#length);
    for (let l = this.#levelShown + 1; l < reached; ++l) this.#decode(0, l);
    this.#levelShown = Math.max(this.#levelShown, reached);
  }

  // The level a decode of the first `length` bytes gives (-1: none yet).
  #levelAt(length) {
    const levels = this.#info?.levelInfo ?? [];
    const wanted = this.#options.level < 0 ? levels.length - 1 : Math.min(this.#options.level, levels.length - 1);
    let reached = -1;
    while (reached + 1 <= wanted && levels[reached + 1].drawableFrom <= length) ++reached;
    return reached;
  }

  // The stream is over: decodes the bytes not decoded yet. When the whole
  // prefix does not decode (a damaged or cut file), falls back to the longest
  // level or plane boundary that does. Returns the best mesh the bytes give;
  // throws when they give none.
  end() {
    if (this.#info === null) this.#readHeader();
    if (this.#length > this.#decodedAt || this.#last === null) {
      if (this.#info !== null) this.#decodeLevelsPassed();
      this.#decode();
    }
    if (this.#error !== null && this.#length > 0) this.#fallBack();
    if (this.#last === null) throw this.#error ?? new Error('srcodec: no bytes arrived');
    // Read again: the header's reading when it arrived counted only the bytes present then.
    if (this.#info !== null) this.#info = this.#decoder.inspect(this.bytes);
    return this.#last;
  }

  #append(chunk) {
    const add = chunk instanceof Uint8Array ? chunk : new Uint8Array(chunk);
    const need = this.#length + add.length;
    if (need > this.#bytes.length) {
      const declared = this.#info !== null && this.#info.declaredBytes <= DECLARED_BYTES_TRUSTED ?
        this.#info.declaredBytes : 0;
      const grown = new Uint8Array(Math.max(need, declared, 2 * this.#bytes.length));
      grown.set(this.#bytes.subarray(0, this.#length));
      this.#bytes = grown;
    }
    this.#bytes.set(add, this.#length);
    this.#length = need;
  }

  // Reads the header once it is complete; a header that is wrong (not an
  // .srm file, or damaged) throws at once rather than after the whole stream.
  #readHeader() {
    if (this.#length < HEADER_START) return false;
    const view = new DataView(this.#bytes.buffer, this.#bytes.byteOffset, this.#length);
    const headerEnd = HEADER_START + view.getUint32(6, true) + 4;
    if (this.#length < headerEnd && this.#looksLikeSrm(view)) return false;
    this.#info = this.#decoder.inspect(this.bytes);  // throws the decoder's message
    const marks = new Set(this.#info.levelInfo.map((l) => l.drawableFrom));
    for (const p of this.#info.planes) marks.add(p.end);
    marks.add(this.#info.declaredBytes);
    this.#marks = [...marks].sort((a, b) => a - b);
    return true;
  }

  #looksLikeSrm(view) {
    return view.getUint8(0) === 0x89 && view.getUint8(1) === 0x53 && view.getUint8(2) === 0x52 &&
           view.getUint8(3) === 0x4d;
  }

  #decode(maxBytes = 0, level = this.#options.level) {
    const started = performance.now();
    this.#decodedAt = maxBytes || this.#length;
    try {
      const { maxVertices, cornerNormals } = this.#options;
      const mesh = this.#decoder.decode(this.bytes, { level, maxBytes, maxVertices, cornerNormals });
      this.#last = mesh;
      this.#error = null;
      this.#options.onRefine?.(mesh, {
        bytesReceived: this.#length, info: this.#info, milliseconds: performance.now() - started,
      });
      return mesh;
    } catch (error) {
      this.#error = error;
      return null;
    }
  }

  #fallBack() {
    const failed = this.#error;
    for (let i = this.#marks.length - 1; i >= 0; --i) {
      const mark = this.#marks[i];
      // A mark gains nothing over the last mesh when that one has its bytes
      // at its level; a coarser level's mesh (from #decodeLevelsPassed) may
      // have used more bytes and still be worse.
      const last = this.#last;
      if (mark >= this.#length || (last !== null && mark <= last.bytesUsed && last.level >= this.#levelAt(mark))) {
        continue;
      }
      if (this.#decode(mark) !== null) break;
    }
    this.#error = failed;  // the stream's own bytes still did not decode: say so
  }
}

// Reads a ReadableStream (a fetch body) to its end through a
// ProgressiveDecoder; options as its, plus onProgress(bytesReceived) after
// each chunk. Resolves with { mesh, info, bytesReceived, error }
// (error: why the whole stream did not decode, with `mesh` the best that
// did). A stream that fails midway (the network) rejects with an Error whose
// `mesh` is the last refinement, after decoding the bytes that did arrive.
// Bytes that are not an .srm file's reject with the decoder's message as soon
// as their first 10 bytes are in, and the stream is cancelled.
export async function decodeStream(decoder, stream, options = {}) {
  const progressive = new ProgressiveDecoder(decoder, options);
  const reader = stream.getReader();
  for (;;) {
    let chunk;
    try {
      chunk = await reader.read();
    } catch (cause) {
      let mesh = null;
      try { mesh = progressive.end(); } catch { mesh = progressive.mesh; }
      const error = new Error(`srcodec: the stream failed after ${progressive.bytesReceived} bytes: ${cause?.message ?? cause}`);
      error.cause = cause;
      error.mesh = mesh;
      error.bytesReceived = progressive.bytesReceived;
      throw error;
    }
    if (chunk.done) break;
    try {
      progressive.push(chunk.value);
    } catch (error) {
      // Bytes that are not an .srm file's: stop the download as well.
      reader.cancel(error).catch(() => {});
      throw error;
    }
    options.onProgress?.(progressive.bytesReceived);
  }
  const mesh = progressive.end();
  return { mesh, info: progressive.info, bytesReceived: progressive.bytesReceived, error: progressive.error };
}
