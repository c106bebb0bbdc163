// Uses the package wrongly: the type test expects each marked line to fail,
// so the declarations are known to be read (not `any`).
import { createDecoder } from 'srcodec';

export async function misuse(bytes: Uint8Array): Promise<void> {
  const decoder = await createDecoder();
  const positions: Float64Array = decoder.decode(bytes).positions;  // error: Float32Array
  decoder.decode(bytes, { levels: 2 });  // error: the option is `level`
  const planes: string = decoder.inspect(bytes).planes[0].end;  // error: a number
  void positions; void planes;
}
