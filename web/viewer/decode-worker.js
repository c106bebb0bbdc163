// The viewer's decoding, off the page's thread: a large or hostile file
// then slows the refinements, never the tab. Reads one .srm (a URL or a
// dropped File) through a ProgressiveDecoder and posts each refinement.
//
// In:  { type: 'open', url | file, maxVertices }   once per worker
//      { type: 'prefix', maxBytes, id }            after 'done': decode a prefix
// Out: { type: 'header', info, total }
//      { type: 'progress', bytesReceived, total, error }
//      { type: 'refine', mesh, bytesReceived, milliseconds }   (mesh arrays transferred)
//      { type: 'done', bytesReceived, total, error, complete }  the stream is over
//      { type: 'failed', stage, message, bytesReceived }       no mesh, or the network broke
//      { type: 'prefixed', id, maxBytes, mesh, milliseconds | error }
import { createDecoder, ProgressiveDecoder } from '../dist/index.js';

let decoder = null;
let progressive = null;
let maxVertices;

const messageOf = (error) => String(error?.message ?? error).replace(/^srcodec: /, '');

function postMesh(type, mesh, extra) {
  const { positions, indices, cornerNormals, ...numbers } = mesh;
  const arrays = [positions, indices, ...(cornerNormals ? Object.values(cornerNormals) : [])];
  postMessage({ type, mesh: { positions, indices, cornerNormals, ...numbers }, ...extra }, arrays.map((a) => a.buffer));
}

async function open({ url, file, maxVertices: limit }) {
  maxVertices = limit;
  let stage = 'load';
  let total = 0;
  try {
    try {
      decoder = await createDecoder();
    } catch (error) {
      throw new Error(`the decoder did not load: ${messageOf(error)}`);
    }
    let stream;
    if (file) {
      stream = file.stream();
      total = file.size;
    } else {
      let response;
      try {
        response = await fetch(url);
      } catch (error) {
        throw new Error(`cannot load ${url}: ${messageOf(error)}`);
      }
      if (!response.ok) throw new Error(`cannot load ${url}: HTTP ${response.status} ${response.statusText}`);
      total = Number(response.headers.get('Content-Length')) || 0;
      stream = response.body;
    }
    stage = 'decode';
    // The header goes out before the first refinement: the page frames the
    // camera on it, and must not move it after the first mesh is drawn.
    let headerPosted = false;
    const postHeader = () => {
      if (headerPosted || progressive.info === null) return;
      headerPosted = true;
      total ||= progressive.info.declaredBytes;
      postMessage({ type: 'header', info: progressive.info, total });
    };
    progressive = new ProgressiveDecoder(decoder, {
      maxVertices,
      cornerNormals: true,  // the page draws normals split at the creases, if any
      onRefine: (mesh, event) => {
        postHeader();
        postMesh('refine', mesh, { bytesReceived: event.bytesReceived, milliseconds: event.milliseconds });
      },
    });
    const reader = stream.getReader();
    for (;;) {
      let chunk;
      stage = 'network';
      try {
        chunk = await reader.read();
      } catch (cause) {
        // The bytes that did arrive still give their mesh.
        const received = progressive.bytesReceived;
        try { progressive.end(); } catch { /* nothing decodable arrived */ }
        postMessage({ type: 'failed', stage, message: messageOf(cause), bytesReceived: received, total });
        return;
      }
      stage = 'decode';
      if (chunk.done) break;
      progressive.push(chunk.value);  // throws on a header that is not an .srm's
      postHeader();
      postMessage({ type: 'progress', bytesReceived: progressive.bytesReceived, total,
                    error: progressive.error && messageOf(progressive.error) });
    }
    const received = progressive.bytesReceived;
    if (received === 0) throw new Error('the file is empty');
    progressive.end();  // a header cut short, or no mesh at all: throws the decoder's reason
    postHeader();
    const declared = progressive.info?.declaredBytes ?? received;
    postMessage({
      type: 'done', bytesReceived: received, total, declaredBytes: declared,
      complete: received >= declared, error: progressive.error && messageOf(progressive.error),
    });
  } catch (error) {
    postMessage({ type: 'failed', stage, message: messageOf(error), bytesReceived: progressive?.bytesReceived ?? 0, total });
  }
}

function prefix({ maxBytes, id }) {
  const started = performance.now();
  try {
    const mesh = decoder.decode(progressive.bytes, { maxBytes, maxVertices, cornerNormals: true });
    postMesh('prefixed', mesh, { id, maxBytes, milliseconds: performance.now() - started });
  } catch (error) {
    postMessage({ type: 'prefixed', id, maxBytes, error: messageOf(error) });
  }
}

onmessage = ({ data }) => {
  if (data.type === 'open') open(data);
  else if (data.type === 'prefix') prefix(data);
};
