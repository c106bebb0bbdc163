// srcodec in JavaScript: the WebAssembly decoder and progressive decoding.
// The three.js loader is apart, in 'srcodec/three' (SRMLoader.js), so that
// this entry point needs no three.js.
export { createDecoder, DEFAULT_MAX_VERTICES, MAX_VERTICES_LIMIT } from './decoder.js';
export { ProgressiveDecoder, decodeStream } from './stream.js';
