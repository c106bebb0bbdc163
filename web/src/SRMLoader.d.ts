// Types of srcodec's three.js loader (src/SRMLoader.js).
import { BufferGeometry, Loader, LoadingManager } from 'three';
import type { Decoder, DecodeError, ProgressiveOptions, RefineEvent } from './index.js';

/** What the loader records in geometry.userData.srcodec. */
export interface SRMGeometryInfo {
  level: number;
  bytesUsed: number;
  bytesReceived: number;
  lastCompletePlane: number;
  baseCut: boolean;
  /** DecodedMesh.creaseEdges: two vertex ids per edge of the decoded mesh along which the surface is sharp. */
  creaseEdges: Uint32Array;
  triangles: number;
  /** How long the decode took (refinements only). */
  milliseconds?: number;
  /** Why the rest of the file did not decode, or null. */
  error: DecodeError | null;
}

export class SRMLoader extends Loader<BufferGeometry> {
  constructor(manager?: LoadingManager);
  decodeOptions: Omit<ProgressiveOptions, 'onRefine'>;
  /** Compute vertex normals for lighting (default true): .srm files carry positions only. */
  computeNormals: boolean;
  setDecoder(decoder: Decoder | Promise<Decoder>): this;
  setDecodeOptions(options: Omit<ProgressiveOptions, 'onRefine'>): this;
  load(url: string,
       onLoad?: (geometry: BufferGeometry) => void,
       onProgress?: (event: ProgressEvent) => void,
       onError?: (error: Error & { geometry?: BufferGeometry | null }) => void,
       onRefine?: (geometry: BufferGeometry, event: RefineEvent) => void): void;
  parse(buffer: ArrayBuffer | Uint8Array, onLoad: (geometry: BufferGeometry) => void,
        onError?: (error: Error) => void): void;
}
