// Types of srcodec's three.js loader (src/SRMLoader.js).
import { BufferGeometry, Loader, LoadingManager } from 'three';
import type { DecodedMesh, Decoder, DecodeError, ProgressiveOptions, RefineEvent } from './index.js';

/**
 * A decoded mesh as an indexed BufferGeometry. With `mesh.cornerNormals` (a mesh with crease edges decoded with
 * `cornerNormals: true`), a vertex per normal, so that the creases shade sharp; else the mesh's vertices, with
 * computeVertexNormals when `normals` is true (the default).
 */
export function meshGeometry(mesh: DecodedMesh, normals?: boolean): BufferGeometry;

/** What the loader records in geometry.userData.srcodec. */
export interface SRMGeometryInfo {
  level: number;
  bytesUsed: number;
  bytesReceived: number;
  lastCompletePlane: number;
  baseCut: boolean;
  /** DecodedMesh.creaseEdges: two vertex ids per edge of the decoded mesh along which the surface is sharp. */
  creaseEdges: Uint32Array;
  /**
   * When the normals are split at creases, the decoded mesh's vertex of each vertex of the geometry (a crease vertex
   * has one per sector); null when the geometry's vertices are the mesh's.
   */
  meshVertices: Uint32Array | null;
  triangles: number;
  /** How long the decode took (refinements only). */
  milliseconds?: number;
  /** Why the rest of the file did not decode, or null. */
  error: DecodeError | null;
}

export class SRMLoader extends Loader<BufferGeometry> {
  constructor(manager?: LoadingManager);
  decodeOptions: Omit<ProgressiveOptions, 'onRefine'>;
  /**
   * Compute normals for lighting (default true): .srm files carry positions only. A file with creases gets normals
   * split at them (meshGeometry), one without computeVertexNormals'.
   */
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
