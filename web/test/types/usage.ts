// Uses every declared part of the package as README.md shows it: the type
// test compiles this against dist/*.d.ts with --strict, so a declaration
// that drifts from the documented use fails.
import * as THREE from 'three';
import {
  createDecoder, decodeStream, ProgressiveDecoder, DEFAULT_MAX_VERTICES,
  type CornerNormals, type DecodedMesh, type FileInfo, type StreamResult,
} from 'srcodec';
import { meshGeometry, SRMLoader } from 'srcodec/three';

export async function use(bytes: Uint8Array, response: Response): Promise<number> {
  const decoder = await createDecoder({ wasm: new URL('./srcodec_decoder.wasm', 'https://example.com/') });
  const mesh: DecodedMesh = decoder.decode(bytes, { level: 2, maxBytes: 4096, maxVertices: DEFAULT_MAX_VERTICES });
  const positions: Float32Array = mesh.positions;
  const indices: Uint32Array = mesh.indices;
  const info: FileInfo = decoder.inspect(bytes);
  const firstDrawable: number = info.levelInfo[0].drawableFrom + info.planes.length;
  const sharp: Uint32Array = mesh.creaseEdges;
  const creases: number = (info.creaseEdges ?? 0) + info.creaseBytes + (mesh.creasesCut ? 1 : 0);
  const split: CornerNormals | null = decoder.decode(bytes, { cornerNormals: true }).cornerNormals;
  const normals: number = split === null ? 0 : split.normals.length + split.vertices.length + split.corners.length;
  const geometry: THREE.BufferGeometry = meshGeometry(mesh);
  const vertexOf: Uint32Array | null = geometry.userData.srcodec?.meshVertices ?? null;

  const progressive = new ProgressiveDecoder(decoder, {
    everyBytes: 1 << 16, cornerNormals: true, onRefine: (m, e) => m.level + e.bytesReceived,
  });
  progressive.push(bytes.subarray(0, 100));
  const last: DecodedMesh = progressive.end();

  if (response.body === null) return 0;
  const result: StreamResult = await decodeStream(decoder, response.body, {
    onRefine: (m) => m.triangleCount,
    onProgress: (received) => received,
  });
  const why: string | undefined = result.error?.message;

  const loader = new SRMLoader().setDecoder(decoder).setDecodeOptions({ maxVertices: 1 << 20 });
  const material = new THREE.MeshStandardMaterial();
  const shown = new THREE.Mesh(new THREE.BufferGeometry(), material);
  loader.load('bunny.srm', (geometry) => { shown.geometry = geometry; }, (event) => event.loaded / event.total,
    (error) => error.geometry?.dispose(), (geometry, event) => geometry.userData.srcodec.level + event.milliseconds);
  return positions.length + indices.length + firstDrawable + last.level + (why?.length ?? 0) + sharp.length + creases +
    normals + (vertexOf?.length ?? 0);
}
