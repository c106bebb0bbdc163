// A three.js loader for .srm files, in the manner of three.js's DRACOLoader,
// that also hands over a refined geometry each time the stream allows one.
//
//   import { SRMLoader } from 'srcodec/three';
//   const loader = new SRMLoader();
//   loader.load('bunny.srm', (geometry) => { mesh.geometry = geometry; }, undefined, console.error,
//               (geometry) => { mesh.geometry = geometry; });  // onRefine: coarse first
import { BufferAttribute, BufferGeometry, Loader } from 'three';

import { createDecoder } from './decoder.js';
import { ProgressiveDecoder, decodeStream } from './stream.js';

// A decoded mesh as a three.js BufferGeometry, indexed. With its corner
// normals (decode's cornerNormals option, for a mesh with crease edges), a
// vertex per normal, so that the creases shade sharp; else the mesh's own
// vertices, and with `normals` the smooth normals of computeVertexNormals.
export function meshGeometry(mesh, normals = true) {
  const geometry = new BufferGeometry();
  const split = normals ? mesh.cornerNormals : null;
  if (split) {
    const { vertices } = split;
    const positions = new Float32Array(3 * vertices.length);
    for (let i = 0, at = 0; i < vertices.length; ++i, at += 3) {
      const from = 3 * vertices[i];
      positions[at] = mesh.positions[from];
      positions[at + 1] = mesh.positions[from + 1];
      positions[at + 2] = mesh.positions[from + 2];
    }
    geometry.setAttribute('position', new BufferAttribute(positions, 3));
    geometry.setAttribute('normal', new BufferAttribute(split.normals, 3));
    geometry.setIndex(new BufferAttribute(split.corners, 1));
    return geometry;
  }
  geometry.setAttribute('position', new BufferAttribute(mesh.positions, 3));
  geometry.setIndex(new BufferAttribute(mesh.indices, 1));
  if (normals) geometry.computeVertexNormals();
  return geometry;
}

// What three.js's loaders hand to onProgress; a plain object where there is
// no ProgressEvent (outside browsers).
function progressEvent(loaded, total) {
  const init = { loaded, total, lengthComputable: total > 0 };
  return typeof ProgressEvent === 'function' ? new ProgressEvent('progress', init) : init;
}

export class SRMLoader extends Loader {
  #decoder = null;

  constructor(manager) {
    super(manager);
    this.decodeOptions = { level: -1, maxVertices: undefined, everyBytes: 0 };
    // .srm files carry positions only: light needs normals (split at the
    // file's creases, if it has any).
    this.computeNormals = true;
  }

  // The decoder to use (from createDecoder), or a promise of one; by
  // default the loader makes its own on first use.
  setDecoder(decoder) {
    this.#decoder = Promise.resolve(decoder);
    return this;
  }

  // Options for every decode: level, maxVertices, everyBytes (README).
  setDecodeOptions(options) {
    Object.assign(this.decodeOptions, options);
    return this;
  }

  #getDecoder() {
    this.#decoder ??= createDecoder();
    return this.#decoder;
  }

  // onLoad(geometry) once the file is in; onRefine(geometry, event) for
  // each refinement on the way (the last is the one onLoad gets); onError
  // on a network or decode error that leaves no mesh. A file that decodes
  // only in part loads the part, and `geometry.userData.srcodec.error` says
  // why the rest did not.
  load(url, onLoad, onProgress, onError, onRefine) {
    const resolved = this.manager.resolveURL(this.path + url);
    this.manager.itemStart(resolved);
    const fail = (error) => {
      if (onError) onError(error); else console.error(error);
      this.manager.itemError(resolved);
      this.manager.itemEnd(resolved);
    };
    this.#stream(resolved, onProgress, onRefine).then((geometry) => {
      onLoad?.(geometry);
      this.manager.itemEnd(resolved);
    }, fail);
  }

  // Decodes a whole file in memory (an ArrayBuffer or Uint8Array).
  parse(buffer, onLoad, onError) {
    this.#getDecoder().then((decoder) => {
      const progressive = new ProgressiveDecoder(decoder, this.#options());
      progressive.push(buffer instanceof ArrayBuffer ? new Uint8Array(buffer) : buffer);
      onLoad(this.#geometry(progressive.end(), progressive.error, progressive.bytesReceived));
    }).catch((error) => { if (onError) onError(error); else throw error; });
  }

  async #stream(url, onProgress, onRefine) {
    const decoder = await this.#getDecoder();
    const response = await fetch(url, {
      headers: new Headers(this.requestHeader),
      credentials: this.withCredentials ? 'include' : 'same-origin',
    });
    if (!response.ok) throw new Error(`SRMLoader: ${url}: HTTP ${response.status} ${response.statusText}`);
    const total = Number(response.headers.get('Content-Length')) || 0;
    let last = null;
    const options = {
      ...this.#options(),
      onRefine: (mesh, event) => {
        last = this.#geometry(mesh, null, event.bytesReceived);
        last.userData.srcodec.milliseconds = event.milliseconds;
        onRefine?.(last, event);
      },
      onProgress: (loaded) => onProgress?.(progressEvent(loaded, total)),
    };
    let result;
    try {
      result = await decodeStream(decoder, response.body, options);
    } catch (error) {
      if (error.mesh === undefined) throw error;  // not the network: the header is not an .srm's
      error.message = `SRMLoader: ${url}: ${error.message}; the last refinement is the best mesh`;
      error.geometry = last;
      throw error;
    }
    if (last === null || last.userData.srcodec.bytesUsed !== result.mesh.bytesUsed) {
      last = this.#geometry(result.mesh, result.error, result.bytesReceived);
    }
    last.userData.srcodec.error = result.error;
    return last;
  }

  // The decode options, with the corner normals the geometry needs.
  #options() {
    return { ...this.decodeOptions, cornerNormals: this.computeNormals };
  }

  #geometry(mesh, error, bytesReceived) {
    const geometry = meshGeometry(mesh, this.computeNormals);
    geometry.userData.srcodec = {
      level: mesh.level, bytesUsed: mesh.bytesUsed, bytesReceived, lastCompletePlane: mesh.lastCompletePlane,
      baseCut: mesh.baseCut, creaseEdges: mesh.creaseEdges, meshVertices: mesh.cornerNormals?.vertices ?? null,
      triangles: mesh.triangleCount, error,
    };
    return geometry;
  }
}
