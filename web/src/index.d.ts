// Types of srcodec's JavaScript package (src/index.js).

/** A mesh decoded from an .srm file or a prefix of one. */
export interface DecodedMesh {
  /** x, y, z of each vertex: the C++ decoder's doubles rounded to float32. */
  positions: Float32Array;
  /** Three vertex indices per triangle, counter-clockwise seen from outside. */
  indices: Uint32Array;
  /** The level decoded: 0 is the base mesh. */
  level: number;
  /** How many of the bytes went into the mesh. */
  bytesUsed: number;
  /** The lowest bit plane decoded completely; -1: none. */
  lastCompletePlane: number;
  /** The bytes end inside the base mesh: `indices` holds the base triangles decoded before the cut. */
  baseCut: boolean;
  /**
   * The edges of this mesh along which the surface is sharp (the file's creases at this level: a base edge that the
   * finer levels split gives its halves): two vertex ids each, the smaller first, sorted by pair. Empty for a file
   * without creases.
   */
  creaseEdges: Uint32Array;
  /** The bytes end inside the creases: the mesh is the base mesh (level 0) and creaseEdges is empty. */
  creasesCut: boolean;
  /** With the cornerNormals option and crease edges in the mesh, normals split at them; else null. */
  cornerNormals: CornerNormals | null;
  vertexCount: number;
  triangleCount: number;
}

/**
 * Normals that keep the creases sharp (the C++ corner_normals): a vertex has one per sector, the fan of its triangles
 * between two crease edges, the area-weighted average of their normals; a vertex on no crease edge has one, the
 * smooth normal. Numbered vertex by vertex.
 */
export interface CornerNormals {
  /** x, y, z of each normal, unit length (zero where its triangles have no area). */
  normals: Float32Array;
  /** The vertex of each normal. */
  vertices: Uint32Array;
  /** For each entry of `indices`, the index of its corner's normal: the triangles over a vertex per normal. */
  corners: Uint32Array;
}

export interface DecodeOptions {
  /** The level to decode: -1 (default) the finest, 0..12 otherwise. */
  level?: number;
  /** Decode only the first maxBytes bytes; 0 (default): all. */
  maxBytes?: number;
  /** Refuse, before allocating, a level with more vertices (default 2^21, at most 2^22). */
  maxVertices?: number;
  /** Also compute cornerNormals when the mesh has crease edges (default false). */
  cornerNormals?: boolean;
}

export interface LevelInfo {
  vertices: number;
  flagBytes: number;
  coefficientBytes: number;
  /** The shortest prefix that decodes to this level. */
  drawableFrom: number;
}

export interface PlaneInfo {
  plane: number;
  bytes: number;
  /** The prefix that holds this plane of every level. */
  end: number;
}

/** What `srcodec info FILE.srm` prints. */
export interface FileInfo {
  version: number;
  fileBytes: number;
  declaredBytes: number;
  headerBytes: number;
  inputVertices: number;
  inputTriangles: number;
  bboxMin: [number, number, number];
  bboxMax: [number, number, number];
  bitsPerVertex: number;
  baseVertices: number;
  baseTriangles: number;
  baseBytes: number;
  /** The crease chunk's bytes (format version 3); 0 for a file without creases. */
  creaseBytes: number;
  /**
   * How many base edges are creases (a decoded level's creaseEdges refine them); null when the base mesh and
   * creases are not all present, or damaged.
   */
  creaseEdges: number | null;
  baseBits: number;
  levels: number;
  quantizerStep: number;
  topPlane: number;
  rawPlanes: number;
  levelInfo: LevelInfo[];
  planes: PlaneInfo[];
}

/** The decoder's errors: `message` is the C++ Status's message. */
export interface DecodeError extends Error {
  code: 'invalid_argument' | 'parse_error' | 'invalid_mesh' | 'unsupported' | 'internal' | string;
}

export interface Decoder {
  readonly version: string;
  /** Throws a DecodeError when the bytes give no mesh. */
  decode(bytes: Uint8Array | ArrayBuffer | ArrayBufferView, options?: DecodeOptions): DecodedMesh;
  /** Throws a DecodeError when the bytes do not hold a whole header. */
  inspect(bytes: Uint8Array | ArrayBuffer | ArrayBufferView): FileInfo;
}

export interface CreateDecoderOptions {
  /** The module, when it is not served beside index.js: its URL, its bytes, or a compiled module. */
  wasm?: string | URL | ArrayBuffer | ArrayBufferView | WebAssembly.Module;
}

export function createDecoder(options?: CreateDecoderOptions): Promise<Decoder>;
export const DEFAULT_MAX_VERTICES: number;
export const MAX_VERTICES_LIMIT: number;

export interface RefineEvent {
  bytesReceived: number;
  info: FileInfo | null;
  /** How long the decode took. */
  milliseconds: number;
}

export interface ProgressiveOptions {
  level?: number;
  maxVertices?: number;
  /** As DecodeOptions.cornerNormals. */
  cornerNormals?: boolean;
  /** Also decode after this many new bytes (0, the default: only where a level or bit plane ends). */
  everyBytes?: number;
  onRefine?: (mesh: DecodedMesh, event: RefineEvent) => void;
}

export class ProgressiveDecoder {
  constructor(decoder: Decoder, options?: ProgressiveOptions);
  readonly bytesReceived: number;
  readonly bytes: Uint8Array;
  readonly info: FileInfo | null;
  readonly mesh: DecodedMesh | null;
  readonly error: DecodeError | null;
  /** Appends a chunk; returns the refined mesh, or null when it did not change. Throws on a header that is not an .srm's. */
  push(chunk: Uint8Array | ArrayBuffer): DecodedMesh | null;
  /** Decodes what is left; returns the best mesh the bytes give, or throws. */
  end(): DecodedMesh;
}

export interface StreamResult {
  mesh: DecodedMesh;
  info: FileInfo | null;
  bytesReceived: number;
  /** Why the whole stream did not decode (`mesh` is then the best that did), or null. */
  error: DecodeError | null;
}

export interface StreamOptions extends ProgressiveOptions {
  /** After each chunk: the bytes received so far. */
  onProgress?: (bytesReceived: number) => void;
}

/**
 * Rejects, after a stream error, with an Error whose `mesh` is the last refinement; on bytes that
 * are not an .srm file's, with the decoder's message, cancelling the stream.
 */
export function decodeStream(decoder: Decoder, stream: ReadableStream<Uint8Array>,
                             options?: StreamOptions): Promise<StreamResult>;
